// Corrections of the plan and of the structures (issue 22), on the labels overlay: a region's
// label, towers added (drag for the radius) or removed, two regions merged, the scale from two
// clicked points, and a structure's height, roof, crenellation or "this is the keep". The page
// keeps the whole list and sends it on every change (PUT /api/corrections), so Undo sends the
// previous list; the server checks it as `castellan reconstruct` would, saves it in
// PROJECT.toml and answers with the overlay redrawn.

const KEYS = ['label', 'tower', 'merge', 'structure'];
const MARK = { label: '#ffffff', tower: '#00e5ff', notower: '#ff1744', merge: '#ffea00', scale: '#76ff03', structure: '#ff9100' };

export function initPlanFixes(ui) {
  const { $, api, step, status, fresh, loadImage, canvasImage, toImagePixels, cross } = ui;
  const canvas = $('planfix-canvas');
  let fixes = { label: [], tower: [], merge: [], structure: [], scale_line: null };
  const history = [];
  let redraw = () => {};
  let pending = [];
  let dragging = null;
  let selected = null;

  const mode = () => document.querySelector('input[name=fix]:checked').value;
  const round = ([x, y]) => [Math.round(x), Math.round(y)];
  const copy = (f) => JSON.parse(JSON.stringify(f));

  function drawMarks(ctx) {
    const w = Math.max(2, ctx.canvas.width / 300);
    ctx.lineWidth = w;
    for (const l of fixes.label) cross(ctx, l.point, MARK.label);
    for (const t of fixes.tower) {
      ctx.strokeStyle = t.remove ? MARK.notower : MARK.tower;
      ctx.beginPath();
      ctx.arc(t.point[0], t.point[1], t.radius || 3 * w, 0, 2 * Math.PI);
      ctx.stroke();
      if (t.remove) cross(ctx, t.point, MARK.notower);
    }
    const line = ([a, b], colour) => {
      ctx.strokeStyle = colour;
      ctx.beginPath();
      ctx.moveTo(...a);
      ctx.lineTo(...b);
      ctx.stroke();
    };
    for (const m of fixes.merge) line(m.points, MARK.merge);
    if (fixes.scale_line) line(fixes.scale_line.points, MARK.scale);
    for (const s of fixes.structure) {
      ctx.strokeStyle = MARK.structure;
      ctx.strokeRect(s.point[0] - 4 * w, s.point[1] - 4 * w, 8 * w, 8 * w);
    }
    for (const p of pending) cross(ctx, p, mode() === 'scale' ? MARK.scale : MARK.merge);
    if (dragging) {
      ctx.strokeStyle = MARK.tower;
      ctx.beginPath();
      ctx.arc(dragging.from[0], dragging.from[1], dragging.radius, 0, 2 * Math.PI);
      ctx.stroke();
    }
  }

  function describe(kind, f, i) {
    const at = `[${f.point || f.points.map((p) => `[${p}]`).join(', ')}]`;
    switch (kind) {
      case 'label': return `[[label]] #${i + 1}: ${f.label} at ${at}`;
      case 'tower': return `[[tower]] #${i + 1}: ${f.remove ? 'no tower' : 'tower'} at ${at}${f.radius ? `, radius ${f.radius} px` : ''}`;
      case 'merge': return `[[merge]] #${i + 1}: regions at ${at} are one`;
      default: {
        const what = ['height', 'roof', 'crenellated', 'keep'].filter((k) => f[k] !== undefined).map((k) => `${k} = ${f[k]}`);
        return `[[structure]] #${i + 1} at ${at}: ${what.join(', ')}`;
      }
    }
  }

  function showList() {
    const list = $('planfix-list');
    list.replaceChildren();
    for (const kind of KEYS) {
      fixes[kind].forEach((f, i) => {
        const li = document.createElement('li');
        li.textContent = `${describe(kind, f, i)} `;
        const del = document.createElement('button');
        del.textContent = '×';
        del.title = 'Delete this correction';
        del.addEventListener('click', () => change((next) => { next[kind].splice(i, 1); }));
        li.append(del);
        list.append(li);
      });
    }
    if (fixes.scale_line) {
      const li = document.createElement('li');
      const s = fixes.scale_line;
      li.textContent = `scale_line: ${s.metres} m between [${s.points[0]}] and [${s.points[1]}] `;
      const del = document.createElement('button');
      del.textContent = '×';
      del.addEventListener('click', () => change((next) => { next.scale_line = null; }));
      li.append(del);
      list.append(li);
    }
    const n = KEYS.reduce((k, key) => k + fixes[key].length, 0) + (fixes.scale_line ? 1 : 0);
    $('planfix-info').dataset.count = String(n);
    $('planfix-undo').disabled = history.length === 0;
  }

  async function showOverlay(url) {
    const img = await loadImage(fresh(url));
    redraw = canvasImage(canvas, img, drawMarks);
    canvas.dataset.loaded = 'true';
  }

  // Applies `edit` to a copy of the corrections and saves it; on refusal nothing changes.
  async function change(edit) {
    const next = copy(fixes);
    edit(next);
    const t = performance.now();
    const r = await step('Saving the correction', () => api('PUT', '/api/corrections', next));
    if (!r) return null;
    history.push(fixes);
    fixes = next;
    await settle(r, t);
    return r;
  }

  async function settle(r, t) {
    await showOverlay(r.overlay);
    const ms = Math.round(performance.now() - t);
    $('planfix-info').textContent = `${r.towers} towers, ${r.faces} regions; saved and redrawn in ${ms} ms (server ${r.ms} ms)`;
    $('planfix-info').dataset.towers = String(r.towers);
    $('planfix-info').dataset.roundTripMs = String(ms);
    $('plan-info').dataset.towers = String(r.towers);
    showList();
  }

  $('planfix-undo').addEventListener('click', async () => {
    if (!history.length) return;
    const previous = history[history.length - 1];
    const t = performance.now();
    const r = await step('Undoing the correction', () => api('PUT', '/api/corrections', previous));
    if (!r) return;
    history.pop();
    fixes = previous;
    await settle(r, t);
  });

  canvas.addEventListener('mousedown', (ev) => {
    if (mode() !== 'tower') return;
    dragging = { from: toImagePixels(canvas, ev), radius: 0 };
  });
  canvas.addEventListener('mousemove', (ev) => {
    if (!dragging) return;
    const [x, y] = toImagePixels(canvas, ev);
    dragging.radius = Math.hypot(x - dragging.from[0], y - dragging.from[1]);
    redraw();
  });
  canvas.addEventListener('mouseup', async (ev) => {
    const pt = round(toImagePixels(canvas, ev));
    const m = mode();
    if (m === 'tower' && dragging) {
      const tower = { point: round(dragging.from) };
      if (dragging.radius >= 3) tower.radius = Math.round(dragging.radius);
      dragging = null;
      await change((next) => next.tower.push(tower));
    } else if (m === 'label') {
      await change((next) => next.label.push({ point: pt, label: $('planfix-label').value }));
    } else if (m === 'notower') {
      await change((next) => next.tower.push({ point: pt, remove: true }));
    } else if (m === 'merge') {
      pending.push(pt);
      if (pending.length === 2) {
        const points = pending;
        pending = [];
        await change((next) => next.merge.push({ points }));
      } else status('Merge: click the second region');
    } else if (m === 'scale') {
      pending.push(pt);
      if (pending.length === 2) {
        const points = pending;
        pending = [];
        const px = Math.hypot(points[1][0] - points[0][0], points[1][1] - points[0][1]).toFixed(1);
        const metres = Number(window.prompt(`Length between the two points (${px} px), in metres:`));
        if (metres > 0) await change((next) => { next.scale_line = { points, metres }; });
      } else status('Scale: click the other end');
    } else if (m === 'structure') {
      await openStructure(pt);
    }
    redraw();
  });

  async function openStructure(pt) {
    const s = await step('Finding the structure', () => api('GET', `/api/structure?x=${pt[0]}&y=${pt[1]}`));
    if (!s) return;
    selected = { point: pt, id: s.id };
    $('structure-panel').hidden = false;
    $('structure-title').textContent = `${s.id}: ${s.role} (${s.label})`;
    $('structure-height').value = s.height.toFixed(2);
    $('structure-units').textContent = s.units;
    $('structure-roof').value = s.roof || '';
    $('structure-crenellated').value = s.crenellated === null || s.crenellated === undefined ? '' : String(s.crenellated);
    $('structure-keep').checked = s.role === 'keep';
    $('structure-sources').textContent = `height from ${s.sources.height || 'default'}`;
    $('structure-panel').dataset.id = s.id;
    $('structure-panel').dataset.role = s.role;
  }

  $('structure-save').addEventListener('click', async () => {
    if (!selected) return;
    const fix = { point: selected.point };
    const h = Number($('structure-height').value);
    if (h > 0) fix.height = h;
    if ($('structure-roof').value) fix.roof = $('structure-roof').value;
    if ($('structure-crenellated').value) fix.crenellated = $('structure-crenellated').value === 'true';
    fix.keep = $('structure-keep').checked;
    // One entry a point: a new one replaces an old one at the same point.
    await change((next) => {
      next.structure = next.structure.filter((s) => s.point[0] !== fix.point[0] || s.point[1] !== fix.point[1]);
      next.structure.push(fix);
    });
  });

  $('settings-save').addEventListener('click', async () => {
    const num = (id) => ($(id).value === '' ? null : Number($(id).value));
    const body = { scale: num('set-scale'), scale_bar: num('set-scale-bar'), thin_lines: num('set-thin-lines'), hatching: $('set-hatching').checked, one_building: $('set-one-building').checked, trim_ink: $('set-trim-ink').checked };
    const r = await step('Saving the plan settings', () => api('PUT', '/api/plan/settings', body));
    if (r) await ui.parsePlan();
  });

  $('planfix-rebuild').addEventListener('click', () => $('reconstruct').click());

  return {
    // After the project is loaded: the saved corrections, settings and label legend.
    async load(project) {
      if (!project) return;
      const c = await api('GET', '/api/corrections');
      fixes = { label: c.label, tower: c.tower, merge: c.merge, structure: c.structure, scale_line: c.scale_line || null };
      history.length = 0;
      const select = $('planfix-label');
      const legend = $('label-legend');
      legend.replaceChildren();
      select.replaceChildren();
      for (const l of c.labels) {
        const li = document.createElement('li');
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = `rgb(${l.colour.join(',')})`;
        li.append(swatch, ` ${l.name}`);
        legend.append(li);
        if (l.region) select.append(new Option(l.name, l.name));
      }
      $('set-scale').value = project.scale ?? '';
      $('set-scale-bar').value = project.scale_bar ?? '';
      $('set-thin-lines').value = project.thin_lines ?? '';
      $('set-hatching').checked = !!project.hatching;
      $('set-one-building').checked = !!project.one_building;
      $('set-trim-ink').checked = !!project.trim_ink;
      showList();
    },
    // After every parse: the new overlay under the marks.
    showOverlay,
  };
}
