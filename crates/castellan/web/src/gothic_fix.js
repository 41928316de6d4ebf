// The Gothic step of the `castellan serve` page (ch. 4, issue 22): a Gothic photo's elements
// drawn over the rectified façade, each with three handles — the springing line, the apex and
// the width — to drag, and a delete key; every change is saved at once as PROJECT.toml's
// `[[gothic.element]]` (rectified photo pixels) and the server sends the elements back
// regrouped (detection is not re-run). An element the detector missed is added by dragging its
// box in add mode (a pointed arch whose rise is that of an equilateral arch, or the box's
// height when lower; its handles are then dragged as any other's). Undo goes back one saved
// list.

const $ = (id) => document.getElementById(id);
const HANDLE = { apex: '#ff9100', springing: '#00b0ff', width: '#ffd600' };
const OUTLINE = ['#ff1744', '#00e676', '#2979ff', '#d500f9'];

// Mirrors facade::gothic::Theta::contains: inside the jambs' box, or under the arch.
function contains(e, x, y) {
  const x0 = e.centre - e.width / 2;
  const x1 = x0 + e.width;
  if (x < x0 || x > x1 || y > e.sill || y < e.apex) return false;
  const rise = e.springing - e.apex;
  if (y >= e.springing || rise <= 1e-3) return y >= e.springing;
  if (rise >= e.width / 2) {
    const r = (e.width * e.width / 4 + rise * rise) / e.width;
    return Math.hypot(x - (x0 + r), y - e.springing) <= r && Math.hypot(x - (x1 - r), y - e.springing) <= r;
  }
  const r = (e.width * e.width / 4 + rise * rise) / (2 * rise);
  return Math.hypot(x - e.centre, y - (e.springing + r - rise)) <= r;
}

const area = (e) => e.width * (e.sill - e.apex);

// The outline of an element (rectified pixels) as a canvas path, shifted by `off`.
function tracePath(ctx, e, off) {
  const [ox, oy] = off;
  const x0 = e.centre - e.width / 2 - ox;
  const x1 = x0 + e.width;
  const [ys, yb] = [e.springing - oy, e.sill - oy];
  const rise = e.springing - e.apex;
  ctx.beginPath();
  ctx.moveTo(x0, yb);
  ctx.lineTo(x1, yb);
  ctx.lineTo(x1, ys);
  if (rise <= 1e-3) ctx.lineTo(x0, ys);
  else if (rise >= e.width / 2) {
    // Two arcs centred on the springing line, meeting at the apex: the right one from the
    // right springer, the left one down to the left springer.
    const r = (e.width * e.width / 4 + rise * rise) / e.width;
    ctx.arc(x1 - r, ys, r, 0, Math.atan2(-rise, r - e.width / 2), true);
    ctx.arc(x0 + r, ys, r, Math.atan2(-rise, e.width / 2 - r), Math.PI, true);
  } else {
    const r = (e.width * e.width / 4 + rise * rise) / (2 * rise);
    const cy = ys + r - rise;
    const half = Math.asin(e.width / 2 / r);
    ctx.arc(e.centre - ox, cy, r, -Math.PI / 2 + half, -Math.PI / 2 - half, true);
  }
  ctx.closePath();
}

// Where each handle sits (rectified pixels).
function handles(e) {
  return {
    apex: [e.centre, e.apex],
    springing: [e.centre + e.width / 2, e.springing],
    width: [e.centre + e.width / 2, (e.springing + e.sill) / 2],
  };
}

export function setupGothic({ api, step, upload, refresh }) {
  const canvas = $('gothic-canvas');
  const ctx = canvas.getContext('2d');
  const state = {
    name: null, image: null, offset: [0, 0], elements: [], corrections: [], undo: [],
    selected: null, drag: null, saves: 0, adding: false, box: null,
  };

  function info(text, error = false) {
    const i = $('gothic-info');
    i.textContent = text;
    i.className = error ? 'error' : '';
  }

  const handleSize = () => Math.max(4, canvas.width / 100);

  function draw() {
    if (!state.image) return;
    ctx.drawImage(state.image, 0, 0);
    const off = state.offset;
    for (const e of state.elements) {
      const chosen = state.selected === e.id;
      tracePath(ctx, e, off);
      ctx.setLineDash(e.correction === null ? [] : [8, 4]);
      ctx.lineWidth = chosen ? 4 : 2;
      ctx.strokeStyle = OUTLINE[e.depth % OUTLINE.length];
      ctx.stroke();
      ctx.setLineDash([]);
      if (!chosen) continue;
      // The springing line across the element, then the three handles.
      ctx.strokeStyle = HANDLE.springing;
      ctx.setLineDash([4, 4]);
      ctx.beginPath();
      ctx.moveTo(e.centre - e.width / 2 - off[0], e.springing - off[1]);
      ctx.lineTo(e.centre + e.width / 2 - off[0], e.springing - off[1]);
      ctx.stroke();
      ctx.setLineDash([]);
      const s = handleSize();
      for (const [kind, [x, y]] of Object.entries(handles(e))) {
        ctx.fillStyle = HANDLE[kind];
        ctx.fillRect(x - off[0] - s, y - off[1] - s, 2 * s, 2 * s);
        ctx.strokeStyle = '#000';
        ctx.lineWidth = 1;
        ctx.strokeRect(x - off[0] - s, y - off[1] - s, 2 * s, 2 * s);
      }
    }
    if (state.box) {
      const [[ax, ay], [bx, by]] = state.box;
      ctx.strokeStyle = '#00e676';
      ctx.lineWidth = 2;
      ctx.setLineDash([8, 4]);
      ctx.strokeRect(Math.min(ax, bx) - off[0], Math.min(ay, by) - off[1], Math.abs(bx - ax), Math.abs(by - ay));
      ctx.setLineDash([]);
    }
    canvas.dataset.elements = JSON.stringify(state.elements);
    canvas.dataset.adding = String(state.adding);
    canvas.dataset.corrections = String(state.corrections.length);
    canvas.dataset.selected = state.selected === null ? '' : String(state.selected);
    $('gothic-undo').disabled = state.undo.length === 0;
    $('gothic-delete').disabled = state.selected === null;
  }

  // The page position of an event in rectified photo pixels.
  function rectified(ev) {
    const r = canvas.getBoundingClientRect();
    return [
      ((ev.clientX - r.left) * canvas.width) / r.width + state.offset[0],
      ((ev.clientY - r.top) * canvas.height) / r.height + state.offset[1],
    ];
  }

  // A point the server's rule (the smallest element containing it) resolves to `e`: inside
  // it with a margin, and inside no smaller element.
  function pickPoint(e) {
    const smaller = state.elements.filter((o) => o.id !== e.id && area(o) < area(e));
    const m = 3;
    const ok = (x, y) => [[0, 0], [m, 0], [-m, 0], [0, m], [0, -m]].every(([dx, dy]) => contains(e, x + dx, y + dy)
      && !smaller.some((o) => contains(o, x + dx, y + dy)));
    const x0 = e.centre - e.width / 2;
    for (let fy = 0.5; fy < 1; fy += 0.05) {
      for (const fx of [0.5, 0.4, 0.6, 0.3, 0.7, 0.2, 0.8, 0.1, 0.9]) {
        const [x, y] = [x0 + fx * e.width, e.apex + fy * (e.sill - e.apex)];
        if (ok(x, y)) return [x, y].map((v) => Math.round(v * 10) / 10);
      }
      for (const fx of [0.5, 0.4, 0.6]) {
        const [x, y] = [x0 + fx * e.width, e.apex + (1 - fy) * (e.sill - e.apex)];
        if (ok(x, y)) return [x, y].map((v) => Math.round(v * 10) / 10);
      }
    }
    return [e.centre, (e.apex + e.sill) / 2];
  }

  function elementAt([x, y]) {
    const inside = state.elements.filter((e) => contains(e, x, y)).sort((a, b) => area(a) - area(b));
    return inside.length ? inside[0] : null;
  }

  function handleAt([x, y]) {
    const s = 1.5 * handleSize();
    const order = [...state.elements].sort((a, b) => (b.id === state.selected) - (a.id === state.selected));
    for (const e of order) {
      for (const [kind, [hx, hy]] of Object.entries(handles(e))) {
        if (Math.abs(hx - x) <= s && Math.abs(hy - y) <= s) return { element: e, kind };
      }
    }
    return null;
  }

  function show(r) {
    state.elements = r.elements;
    state.corrections = r.corrections;
    state.offset = r.offset;
    if (!state.elements.some((e) => e.id === state.selected)) state.selected = null;
    const set = r.elements.filter((e) => e.correction !== null).length;
    const dropped = r.dropped ? `; the learned check dropped ${r.dropped} more as unlike openings (add them back as elements if they are)` : '';
    info(`${r.elements.length} elements in ${r.groups} groups; ${r.corrections.length} corrections ` +
      `(${set} set, ${r.deleted.length} deleted); ${r.ms} ms${r.detected_now ? '' : ' (detection kept)'}${dropped}`);
    draw();
  }

  async function load(r) {
    const img = new Image();
    img.src = `${r.image}?t=${Date.now()}`;
    await img.decode();
    state.image = img;
    canvas.width = img.naturalWidth;
    canvas.height = img.naturalHeight;
    $('gothic-overlay').src = `${r.overlay}?t=${Date.now()}`;
    show(r);
  }

  // Saves the whole list; on success it becomes the state, with the old one on the undo stack.
  async function save(list, note, pushUndo = true) {
    canvas.dataset.state = 'saving';
    const before = state.corrections;
    const r = await step(note, () => api('PUT', `/api/gothic/${encodeURIComponent(state.name)}/elements`, list));
    if (r) {
      if (pushUndo) state.undo.push(before);
      state.saves += 1;
      canvas.dataset.saves = String(state.saves);
      $('gothic-overlay').src = `${r.overlay}?t=${Date.now()}`;
      show(r);
    } else draw();
    canvas.dataset.state = 'ready';
  }

  // The correction list with `e` set to `values` (its current handles kept, so it stays as
  // shown), or deleted.
  function corrected(e, values) {
    const list = state.corrections.map((c) => ({ ...c }));
    const base = e.correction !== null ? list[e.correction] : { point: pickPoint(e) };
    const round = (v) => Math.round(v * 10) / 10;
    const entry = values === 'delete'
      ? { point: base.point, delete: true }
      : {
        point: base.point,
        springing: round(values.springing ?? e.springing),
        apex: round(values.apex ?? e.apex),
        width: round(values.width ?? e.width),
        centre: round(e.centre),
      };
    // Deleting an element the user added takes its entry away.
    if (values === 'delete' && e.correction !== null && list[e.correction].add) list.splice(e.correction, 1);
    else if (e.correction !== null && !list[e.correction].add) list[e.correction] = entry;
    else if (e.correction !== null) list[e.correction] = { ...list[e.correction], ...entry, point: base.point, add: true };
    else list.push(entry);
    return list;
  }

  async function run() {
    if (!state.name) return;
    canvas.dataset.state = 'running';
    const r = await step(`Finding Gothic elements in ${state.name} (ch. 4)`,
      () => api('POST', `/api/gothic/${encodeURIComponent(state.name)}`, { rectified: $('gothic-rectified').checked }));
    if (r) {
      await load(r);
      state.undo = [];
      draw();
    }
    canvas.dataset.state = 'ready';
  }

  // The entry for an element whose box was dragged from `a` to `b` (rectified pixels), or
  // null when the box is too small to be meant.
  function added([a, b]) {
    const round = (v) => Math.round(v * 10) / 10;
    const [x0, x1] = [Math.min(a[0], b[0]), Math.max(a[0], b[0])];
    const [apex, sill] = [Math.min(a[1], b[1]), Math.max(a[1], b[1])];
    const width = x1 - x0;
    if (width < 4 || sill - apex < 4) return null;
    // An equilateral pointed arch rises √3/2 of its span; a box lower than that is all arch.
    const springing = Math.min(sill, apex + (Math.sqrt(3) / 2) * width);
    const centre = (x0 + x1) / 2;
    return {
      point: [round(centre), round((springing + sill) / 2)], add: true,
      springing: round(springing), apex: round(apex), width: round(width), centre: round(centre), sill: round(sill),
    };
  }

  function setAdding(on) {
    state.adding = on;
    state.box = null;
    $('gothic-add').classList.toggle('active', on);
    $('gothic-add').textContent = on ? 'Adding: drag the new element\'s box (Esc to stop)' : 'Add an element';
    draw();
  }

  function deleteSelected() {
    const e = state.elements.find((x) => x.id === state.selected);
    if (!e) return;
    state.selected = null;
    save(corrected(e, 'delete'), 'Deleting the element');
  }

  canvas.addEventListener('mousedown', (ev) => {
    const p = rectified(ev);
    if (state.adding) {
      state.box = [p, p];
      draw();
      return;
    }
    const h = handleAt(p);
    if (h) {
      state.selected = h.element.id;
      state.drag = { ...h, from: p, shape: { ...h.element } };
      draw();
      return;
    }
    const e = elementAt(p);
    state.selected = e ? e.id : null;
    draw();
  });

  canvas.addEventListener('mousemove', (ev) => {
    if (state.adding && state.box) {
      state.box = [state.box[0], rectified(ev)];
      draw();
      return;
    }
    const d = state.drag;
    if (!d) return;
    const [x, y] = rectified(ev);
    const e = state.elements.find((o) => o.id === d.element.id);
    const s = d.shape;
    // The element follows the mouse at once; the server's answer replaces it on release.
    if (d.kind === 'apex') e.apex = Math.min(y, s.springing);
    if (d.kind === 'springing') e.springing = Math.min(Math.max(y, s.apex), s.sill);
    if (d.kind === 'width') e.width = Math.max(2, 2 * Math.abs(x - s.centre));
    d.moved = true;
    draw();
  });

  window.addEventListener('mouseup', () => {
    if (state.adding && state.box) {
      const entry = added(state.box);
      setAdding(false);
      if (entry) save([...state.corrections.map((c) => ({ ...c })), entry], 'Adding an element');
      else info('The box is too small for an element (at least 4 × 4 px)', true);
      return;
    }
    const d = state.drag;
    state.drag = null;
    if (!d || !d.moved) return;
    const e = state.elements.find((o) => o.id === d.element.id);
    const values = { [d.kind]: e[d.kind] };
    save(corrected({ ...d.shape, correction: d.element.correction }, values), `Moving the ${d.kind} handle`);
  });

  window.addEventListener('keydown', (ev) => {
    if (ev.key === 'Escape' && state.adding) setAdding(false);
    if ((ev.key === 'Delete' || ev.key === 'Backspace') && state.selected !== null
      && !['INPUT', 'SELECT', 'TEXTAREA'].includes(document.activeElement.tagName)) {
      ev.preventDefault();
      deleteSelected();
    }
  });

  $('gothic-delete').addEventListener('click', deleteSelected);
  $('gothic-add').addEventListener('click', () => setAdding(!state.adding));
  $('gothic-undo').addEventListener('click', () => {
    const back = state.undo.pop();
    if (back) save(back, 'Undoing the last correction', false);
  });
  $('gothic-run').addEventListener('click', run);
  $('gothic-select').addEventListener('change', (ev) => { state.name = ev.target.value; });
  $('gothic-file').addEventListener('change', async (ev) => {
    const file = ev.target.files[0];
    if (!file) return;
    const r = await upload('gothic', file);
    if (!r) return;
    await refresh();
    state.name = r.name;
    $('gothic-select').value = r.name;
    $('gothic-file').value = '';
  });

  return {
    // The project as loaded: the Gothic photos to pick from.
    show(project) {
      const list = (project && project.gothic) || [];
      $('gothic-select').replaceChildren(...list.map((g) => new Option(g.image, g.image)));
      if (!list.some((g) => g.image === state.name)) state.name = list.length ? list[0].image : null;
      if (state.name) $('gothic-select').value = state.name;
      const entry = list.find((g) => g.image === state.name);
      $('gothic-rectified').checked = Boolean(entry && entry.rectified);
    },
  };
}
