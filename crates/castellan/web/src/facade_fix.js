// Façade corrections in the `castellan serve` page (issue 22): on the façade tree over the
// rectified photo (§3.1.7), drag floor lines and window-column edges, add a window (drag a
// box), delete one (click), mark a floor as having no windows (click it); undo goes back one
// change at a time. Every change is sent whole to PUT /api/facades/{name}/fixes, which re-runs
// the façade step with it and saves it as the façade's [facade.fix] in PROJECT.toml.

const COLOURS = { floor: '#ff9100', column: '#00b8d4', window: '#00e676', added: '#ffea00', blind: 'rgba(40,40,40,0.45)' };
const MODES = [
  ['move', 'drag lines', 'Drag a floor line up or down, or a column edge left or right'],
  ['add', 'add window', 'Drag a box round a window the search missed'],
  ['delete', 'delete window', 'Click a window the search invented (or one you added)'],
  ['blind', 'no windows', 'Click a floor to say it has no windows (a shop or blind floor); click again to undo'],
];

const copy = (v) => JSON.parse(JSON.stringify(v));
const inside = ([x, y], [x0, y0, x1, y1]) => x >= x0 && x <= x1 && y >= y0 && y <= y1;
// Whole pixels: the search places floor lines and column edges on pixel rows and columns.
const round = Math.round;

// The page's helpers come in `ctx`: api, step, loadImage, fresh, toImagePixels, and facade()
// (the selected photo's name).
export function facadeFix(ctx) {
  const el = (tag, props = {}, children = []) => {
    const e = Object.assign(document.createElement(tag), props);
    e.append(...children);
    return e;
  };
  const info = el('span', { id: 'fix-info' });
  const canvas = el('canvas', { id: 'fix-canvas' });
  const modes = MODES.map(([value, label, title]) =>
    el('label', { title }, [el('input', { type: 'radio', name: 'fix-mode', value, checked: value === 'move' }), ` ${label} `]));
  const open = el('button', { id: 'fix-open', textContent: 'Correct floors and windows' });
  const undo = el('button', { id: 'fix-undo', textContent: 'Undo', title: 'Undo the last correction (Ctrl+Z)' });
  const reset = el('button', { id: 'fix-reset', textContent: 'Remove all corrections' });
  const swatch = (colour, text) => el('span', {}, [
    el('span', { style: `display:inline-block;width:1em;height:1em;vertical-align:middle;border:1px solid #888;background:${colour}` }),
    ` ${text} `]);
  const legend = el('figcaption', { id: 'fix-legend' }, [
    swatch(COLOURS.floor, 'floor line (drag)'), swatch(COLOURS.column, 'column edge (drag)'),
    swatch(COLOURS.window, 'window found'), swatch(COLOURS.added, 'window you added'),
    swatch(COLOURS.blind, 'floor with no windows'),
    ' — under them the façade tree: green window, magenta wall, red background',
  ]);
  const section = el('div', { id: 'facade-fix' }, [
    el('h3', { textContent: 'Correct the façade (saved in PROJECT.toml, used by castellan reconstruct)' }),
    el('p', {}, [open, ' ', ...modes, undo, ' ', reset, ' ', info]),
    el('figure', { style: 'max-width:100%' }, [canvas, legend]),
  ]);
  document.getElementById('facades').append(section);

  // The last answer of the server (tree, fix, overlay), the overlay image, the changes before.
  let tree = null;
  let image = null;
  let history = [];
  let drag = null;

  const mode = () => section.querySelector('input[name=fix-mode]:checked').value;
  const facade = () => (tree && tree.facades[0]) || null;
  const handle = () => Math.max(4, canvas.width / 120);

  // Floor lines top to bottom, and window columns: the user's, else the search's (the columns
  // of the floor with the most windows).
  function floorLines() {
    const f = facade();
    if (!f) return [];
    return (tree.fix.floor_lines || f.floors.slice(1).map((fl) => fl.y0)).slice();
  }
  function columns() {
    if (tree.fix.columns) return copy(tree.fix.columns);
    const f = facade();
    if (!f) return [];
    const added = tree.fix.add_windows || [];
    const found = (fl) => fl.windows.filter((w) => !added.some((a) => a.every((v, k) => Math.abs(v - w[k]) < 1e-6)));
    const widest = f.floors.map(found).reduce((a, ws) => (ws.length > a.length ? ws : a), []);
    return widest.map((w) => [w[0], w[2]]).sort((a, b) => a[0] - b[0]);
  }

  function draw() {
    const c = canvas.getContext('2d');
    if (!image) return;
    c.drawImage(image, 0, 0);
    const f = facade();
    if (!f) return;
    const [x0, y0, x1, y1] = f.bbox;
    const h = handle();
    c.lineWidth = Math.max(2, h / 2);
    // Blind floors shaded.
    const blind = tree.fix.blind_floors || [];
    f.floors.forEach((fl, i) => {
      if (blind.includes(f.floors.length - i)) {
        c.fillStyle = COLOURS.blind;
        c.fillRect(x0, fl.y0, x1 - x0, fl.y1 - fl.y0);
      }
    });
    const added = tree.fix.add_windows || [];
    for (const fl of f.floors) {
      for (const w of fl.windows) {
        c.strokeStyle = added.some((a) => a.every((v, k) => Math.abs(v - w[k]) < 1e-6)) ? COLOURS.added : COLOURS.window;
        c.strokeRect(w[0], w[1], w[2] - w[0], w[3] - w[1]);
      }
    }
    const lines = drag && drag.kind === 'floor' ? drag.lines : floorLines();
    c.strokeStyle = COLOURS.floor;
    for (const y of lines) {
      c.beginPath(); c.moveTo(x0, y); c.lineTo(x1, y); c.stroke();
      c.fillStyle = COLOURS.floor;
      c.fillRect(x0 - h / 2, y - h / 2, h, h);
      c.fillRect(x1 - h / 2, y - h / 2, h, h);
    }
    const cols = drag && drag.kind === 'column' ? drag.columns : columns();
    c.strokeStyle = COLOURS.column;
    c.setLineDash([h, h / 2]);
    for (const col of cols) for (const x of col) {
      c.beginPath(); c.moveTo(x, y0); c.lineTo(x, y1); c.stroke();
    }
    c.setLineDash([]);
    if (drag && drag.kind === 'box' && drag.to) {
      c.strokeStyle = COLOURS.added;
      c.setLineDash([6, 4]);
      c.strokeRect(drag.from[0], drag.from[1], drag.to[0] - drag.from[0], drag.to[1] - drag.from[1]);
      c.setLineDash([]);
    }
  }

  async function show(answer) {
    tree = answer;
    image = await ctx.loadImage(ctx.fresh(answer.overlay));
    canvas.width = image.naturalWidth;
    canvas.height = image.naturalHeight;
    const f = facade();
    const floors = f ? f.floors.length : 0;
    const windows = f ? f.floors.reduce((a, fl) => a + fl.windows.length, 0) : 0;
    Object.assign(info.dataset, { floors: String(floors), windows: String(windows), undo: String(history.length) });
    const warned = (answer.warnings || []).length ? `; ${answer.warnings.join('; ')}` : '';
    info.textContent = `${floors} floors, ${windows} windows; ${Object.keys(answer.fix).length ? 'your corrections: ' + Object.keys(answer.fix).join(', ') : 'no corrections'}${warned}`;
    canvas.dataset.fix = JSON.stringify(answer.fix);
    canvas.dataset.tree = JSON.stringify(answer.facades);
    draw();
  }

  const url = () => `/api/facades/${encodeURIComponent(ctx.facade())}`;

  // Sends `fix` whole; on success the tree and overlay follow it and `remember` joins the undo
  // stack.
  async function send(fix, label, remember = true) {
    const before = copy(tree.fix);
    const r = await ctx.step(label, () => ctx.api('PUT', `${url()}/fixes`, fix));
    if (!r) { draw(); return; }
    if (remember) history.push(before);
    await show(r);
  }

  function change(edit, label) {
    const fix = copy(tree.fix);
    edit(fix);
    for (const k of ['add_windows', 'remove_windows', 'blind_floors']) if (fix[k] && !fix[k].length) delete fix[k];
    return send(fix, label);
  }

  open.addEventListener('click', async () => {
    if (!ctx.facade()) return;
    const r = await ctx.step('Façade tree', () => ctx.api('POST', `${url()}/tree`));
    if (!r) return;
    history = [];
    await show(r);
  });
  undo.addEventListener('click', async () => {
    if (!tree || !history.length) return;
    const previous = history[history.length - 1];
    const r = await ctx.step('Undo', () => ctx.api('PUT', `${url()}/fixes`, previous));
    if (!r) return;
    history.pop();
    await show(r);
  });
  window.addEventListener('keydown', (ev) => {
    if ((ev.ctrlKey || ev.metaKey) && ev.key === 'z' && tree && document.activeElement === document.body) {
      ev.preventDefault();
      undo.click();
    }
  });
  reset.addEventListener('click', () => tree && send({}, 'Removing the corrections'));

  // The floor line or column edge near `pt`.
  function hit(pt) {
    const f = facade();
    if (!f) return null;
    const tol = handle() * 1.5;
    const lines = floorLines();
    const i = lines.findIndex((y) => Math.abs(pt[1] - y) <= tol);
    if (i >= 0 && pt[0] >= f.bbox[0] - tol && pt[0] <= f.bbox[2] + tol) return { kind: 'floor', index: i, lines };
    const cols = columns();
    for (let c = 0; c < cols.length; c++) {
      for (const side of [0, 1]) {
        if (Math.abs(pt[0] - cols[c][side]) <= tol) return { kind: 'column', index: c, side, columns: cols };
      }
    }
    return null;
  }

  canvas.addEventListener('mousedown', (ev) => {
    if (!tree) return;
    const pt = ctx.toImagePixels(canvas, ev);
    const f = facade();
    if (mode() === 'move') {
      drag = hit(pt);
    } else if (mode() === 'add') {
      drag = { kind: 'box', from: pt, to: null };
    } else if (mode() === 'delete' && f) {
      const added = (tree.fix.add_windows || []).findIndex((b) => inside(pt, b));
      if (added >= 0) change((fix) => fix.add_windows.splice(added, 1), 'Deleting your window');
      else if (f.floors.some((fl) => fl.windows.some((w) => inside(pt, w)))) {
        change((fix) => { (fix.remove_windows ||= []).push(pt.map(round)); }, 'Deleting a window');
      }
    } else if (mode() === 'blind' && f) {
      const i = f.floors.findIndex((fl) => pt[1] >= fl.y0 && pt[1] < fl.y1);
      if (i < 0) return;
      // Counted from the ground; the floor lines are kept as they are, so the count holds.
      const floor = f.floors.length - i;
      const lines = floorLines();
      change((fix) => {
        fix.floor_lines = lines;
        const list = fix.blind_floors || [];
        fix.blind_floors = list.includes(floor) ? list.filter((n) => n !== floor) : [...list, floor].sort((a, b) => a - b);
      }, 'Marking a floor without windows');
    }
  });
  canvas.addEventListener('mousemove', (ev) => {
    if (!drag) return;
    const [x, y] = ctx.toImagePixels(canvas, ev);
    const f = facade();
    if (drag.kind === 'floor') {
      // Between its neighbours, inside the façade.
      const lo = drag.index > 0 ? drag.lines[drag.index - 1] + 2 : f.bbox[1] + 2;
      const hi = drag.index + 1 < drag.lines.length ? drag.lines[drag.index + 1] - 2 : f.bbox[3] - 2;
      drag.lines[drag.index] = round(Math.min(hi, Math.max(lo, y)));
    } else if (drag.kind === 'column') {
      const col = drag.columns[drag.index];
      const lo = drag.side ? col[0] + 2 : (drag.index > 0 ? drag.columns[drag.index - 1][1] : 0);
      const hi = drag.side ? (drag.index + 1 < drag.columns.length ? drag.columns[drag.index + 1][0] : canvas.width) : col[1] - 2;
      col[drag.side] = round(Math.min(hi, Math.max(lo, x)));
    } else if (drag.kind === 'box') drag.to = [x, y];
    drag.moved = true;
    draw();
  });
  window.addEventListener('mouseup', () => {
    if (!drag) return;
    const d = drag;
    drag = null;
    if (!d.moved) { draw(); return; }
    if (d.kind === 'floor') change((fix) => { fix.floor_lines = d.lines; }, 'Moving a floor line');
    else if (d.kind === 'column') change((fix) => { fix.columns = d.columns; }, 'Moving a column edge');
    else if (d.kind === 'box' && d.to) {
      // Inside the rectified photo, where the server checks it.
      const cx = (v) => Math.min(canvas.width, Math.max(0, v));
      const cy = (v) => Math.min(canvas.height, Math.max(0, v));
      const [x0, x1] = [cx(d.from[0]), cx(d.to[0])].sort((a, b) => a - b);
      const [y0, y1] = [cy(d.from[1]), cy(d.to[1])].sort((a, b) => a - b);
      if (x1 - x0 >= 2 && y1 - y0 >= 2) {
        change((fix) => { (fix.add_windows ||= []).push([x0, y0, x1, y1].map(round)); }, 'Adding a window');
      } else draw();
    }
  });

  return {
    // A newly selected photo: its corrections are shown on request.
    select() {
      tree = null;
      image = null;
      history = [];
      canvas.width = 0;
      info.textContent = '';
    },
  };
}
