// The `castellan serve` page: plan → façades (upload, rectification overlay, training boxes
// drawn with the mouse, façade overlay) → correspondences (click a façade point, then plan
// point(s)) → reconstruction shown in the model viewer. Every change is saved by the server.
import { showModel } from './viewer.js';

const $ = (id) => document.getElementById(id);
const COLOURS = { window: '#00c853', wall: '#d500f9', background: '#ff1744' };
const state = { project: null, training: {}, facade: null, photos: {}, pending: null, corr: [] };

function status(text, error = false) {
  const s = $('status');
  s.textContent = text;
  s.className = error ? 'error' : '';
}

async function api(method, url, body) {
  const init = { method };
  if (body instanceof FormData) init.body = body;
  else if (body !== undefined) {
    init.body = JSON.stringify(body);
    init.headers = { 'content-type': 'application/json' };
  }
  const res = await fetch(url, init);
  const data = await res.json().catch(() => ({ error: `${res.status} ${res.statusText}` }));
  if (!res.ok) throw new Error(data.error || `${res.status}`);
  return data;
}

// Runs a step, showing the server's progress while it lasts and the outcome after; null on failure.
async function step(label, work) {
  status(`${label}…`);
  const poll = setInterval(async () => {
    const p = await api('GET', '/api/progress').catch(() => null);
    if (p && p.running) status(`${label}: ${p.running} ${(p.elapsed_ms / 1000).toFixed(1)} s`);
  }, 500);
  try {
    const out = await work();
    status(`${label}: done`);
    return out;
  } catch (e) {
    // Shown to the user; callers get null and stop.
    status(`${label}: ${e.message}`, true);
    return null;
  } finally {
    clearInterval(poll);
  }
}

const fresh = (url) => `${url}?t=${Date.now()}`;

function loadImage(url) {
  return new Promise((resolve, reject) => {
    const img = new Image();
    img.onload = () => resolve(img);
    img.onerror = () => reject(new Error(`cannot load ${url}`));
    img.src = url;
  });
}

function showOverlay(id, url) {
  return new Promise((resolve) => {
    const img = $(id);
    img.onload = () => { img.dataset.loaded = 'true'; resolve(); };
    img.onerror = () => resolve();
    img.dataset.loaded = 'false';
    img.src = fresh(url);
  });
}

async function upload(kind, file) {
  const form = new FormData();
  form.append('kind', kind);
  form.append('file', file);
  return step(`Uploading ${file.name}`, () => api('POST', '/api/upload', form));
}

// A canvas showing an image at its own pixel size (scaled by CSS), with a redraw hook.
function canvasImage(canvas, img, draw) {
  canvas.width = img.naturalWidth;
  canvas.height = img.naturalHeight;
  const ctx = canvas.getContext('2d');
  const redraw = () => {
    ctx.drawImage(img, 0, 0);
    draw(ctx);
  };
  redraw();
  return redraw;
}

function toImagePixels(canvas, ev) {
  const r = canvas.getBoundingClientRect();
  return [
    ((ev.clientX - r.left) * canvas.width) / r.width,
    ((ev.clientY - r.top) * canvas.height) / r.height,
  ];
}

function cross(ctx, [x, y], colour) {
  const s = Math.max(6, ctx.canvas.width / 80);
  ctx.strokeStyle = colour;
  ctx.lineWidth = Math.max(2, s / 3);
  ctx.beginPath();
  ctx.moveTo(x - s, y); ctx.lineTo(x + s, y);
  ctx.moveTo(x, y - s); ctx.lineTo(x, y + s);
  ctx.stroke();
}

// ---- 1 plan
async function showPlan() {
  const p = state.project;
  if (!p) return;
  $('plan-image').src = fresh(`/files/${p.plan}`);
  state.planImage = await loadImage(fresh(`/files/${p.plan}`));
  drawCorrespondences();
}

$('plan-file').addEventListener('change', async (ev) => {
  const file = ev.target.files[0];
  if (!file) return;
  if (!(await upload('plan', file))) return;
  await refresh().catch((e) => status(e.message, true));
});

$('plan-run').addEventListener('click', async () => {
  const r = await step('Parsing the plan', () => api('POST', '/api/plan'));
  if (!r) return;
  $('plan-info').textContent = `${r.faces} regions, ${r.edges} edges in ${r.ms} ms`;
  await showOverlay('plan-overlay', r.overlay);
  markDone('plan');
});

// ---- 2 façades
let redrawPhoto = () => {};
let drag = null;

function boxes() {
  const t = state.training[state.facade] || { classes: {} };
  state.training[state.facade] = t;
  return t.classes;
}

function showBoxCount(note) {
  const n = Object.values(boxes()).reduce((a, l) => a + l.length, 0);
  $('boxes-info').dataset.count = String(n);
  $('boxes-info').textContent = `${n} boxes (${note})`;
}

function drawBoxes(ctx) {
  for (const [cls, list] of Object.entries(boxes())) {
    ctx.strokeStyle = COLOURS[cls] || '#000';
    ctx.lineWidth = Math.max(2, ctx.canvas.width / 300);
    for (const [x0, y0, x1, y1] of list) ctx.strokeRect(x0, y0, x1 - x0, y1 - y0);
  }
  if (drag && drag.to) {
    ctx.setLineDash([6, 4]);
    ctx.strokeStyle = COLOURS[drag.cls];
    const [[x0, y0], [x1, y1]] = [drag.from, drag.to];
    ctx.strokeRect(x0, y0, x1 - x0, y1 - y0);
    ctx.setLineDash([]);
  }
}

async function selectFacade(name) {
  state.facade = name;
  $('facade-select').value = name;
  if (!name) return;
  const img = await loadImage(fresh(`/files/${name}`));
  state.photos[name] = img;
  redrawPhoto = canvasImage($('facade-canvas'), img, drawBoxes);
  showBoxCount('saved');
  for (const id of ['rectify-overlay', 'facade-overlay']) $(id).removeAttribute('src');
  drawCorrespondences();
}

$('facade-select').addEventListener('change', (ev) => selectFacade(ev.target.value));

$('facade-file').addEventListener('change', async (ev) => {
  const file = ev.target.files[0];
  if (!file) return;
  const r = await upload('facade', file);
  if (!r) return;
  await refresh();
  await selectFacade(r.name);
});

const canvas = $('facade-canvas');
canvas.addEventListener('mousedown', (ev) => {
  const cls = document.querySelector('input[name=class]:checked').value;
  drag = { cls, from: toImagePixels(canvas, ev), to: null };
});
canvas.addEventListener('mousemove', (ev) => {
  if (!drag) return;
  drag.to = toImagePixels(canvas, ev);
  redrawPhoto();
});
window.addEventListener('mouseup', () => {
  if (!drag) return;
  const d = drag;
  drag = null;
  if (d.to) {
    const [x0, x1] = [d.from[0], d.to[0]].sort((a, b) => a - b);
    const [y0, y1] = [d.from[1], d.to[1]].sort((a, b) => a - b);
    if (x1 - x0 >= 2 && y1 - y0 >= 2) (boxes()[d.cls] ||= []).push([x0, y0, x1, y1].map(Math.round));
  }
  redrawPhoto();
  showBoxCount('unsaved');
});

$('boxes-undo').addEventListener('click', () => {
  const cls = document.querySelector('input[name=class]:checked').value;
  (boxes()[cls] || []).pop();
  redrawPhoto();
  showBoxCount('unsaved');
});

$('boxes-save').addEventListener('click', async () => {
  const name = state.facade;
  const r = await step('Saving boxes', () =>
    api('PUT', `/api/facades/${encodeURIComponent(name)}/training`, state.training[name]));
  if (!r) return;
  $('boxes-info').dataset.count = String(r.boxes);
  $('boxes-info').textContent = `${r.boxes} boxes saved to ${r.saved}`;
});

$('facade-rectify').addEventListener('click', async () => {
  const name = state.facade;
  const r = await step('Rectifying', () => api('POST', `/api/facades/${encodeURIComponent(name)}/rectify`));
  if (!r) return;
  $('facade-info').textContent =
    `${r.horizontal} horizontal, ${r.vertical} vertical segments; ${r.width}×${r.height} in ${r.ms} ms`;
  await showOverlay('rectify-overlay', r.overlay);
});

$('facade-run').addEventListener('click', async () => {
  const name = state.facade;
  const r = await step('Façade search', () => api('POST', `/api/facades/${encodeURIComponent(name)}/facade`));
  if (!r) return;
  $('facade-info').textContent = `${r.facades} façade(s), ${r.floors} floor(s), ${r.windows} window(s) in ${r.ms} ms`;
  await showOverlay('facade-overlay', r.overlay);
  markDone('facades');
});

// ---- 3 correspondences
let redrawCorrPhoto = () => {};
let redrawCorrPlan = () => {};

function drawCorrespondences() {
  const photo = state.photos[state.facade];
  if (photo) {
    redrawCorrPhoto = canvasImage($('corr-photo'), photo, (ctx) => {
      for (const c of state.corr) if (c.facade === state.facade) cross(ctx, c.facade_point, '#1565c0');
      if (state.pending && state.pending.facade === state.facade) cross(ctx, state.pending.facade_point, '#ff6d00');
    });
  }
  if (state.planImage) {
    redrawCorrPlan = canvasImage($('corr-plan'), state.planImage, (ctx) => {
      for (const c of state.corr) for (const p of c.plan_points) cross(ctx, p, '#1565c0');
      if (state.pending) for (const p of state.pending.plan_points) cross(ctx, p, '#ff6d00');
    });
  }
  const list = $('corr-list');
  list.replaceChildren(...state.corr.map((c) => {
    const li = document.createElement('li');
    const fmt = ([x, y]) => `(${x.toFixed(0)}, ${y.toFixed(0)})`;
    li.textContent = `${c.facade} ${fmt(c.facade_point)} → plan ${c.plan_points.map(fmt).join(' ')} `;
    const del = document.createElement('button');
    del.textContent = 'Remove';
    del.addEventListener('click', () => { state.corr = state.corr.filter((x) => x !== c); drawCorrespondences(); });
    li.append(del);
    return li;
  }));
}

$('corr-photo').addEventListener('click', (ev) => {
  if (!state.facade) return;
  state.pending = { facade: state.facade, facade_point: toImagePixels($('corr-photo'), ev), plan_points: [] };
  redrawCorrPhoto();
  redrawCorrPlan();
});

$('corr-plan').addEventListener('click', (ev) => {
  if (!state.pending) { status('Click the façade point first', true); return; }
  if (state.pending.plan_points.length >= 2) state.pending.plan_points = [];
  state.pending.plan_points.push(toImagePixels($('corr-plan'), ev));
  redrawCorrPlan();
});

$('corr-add').addEventListener('click', () => {
  const p = state.pending;
  if (!p || !p.plan_points.length) { status('Click a façade point and a plan point first', true); return; }
  state.corr.push(p);
  state.pending = null;
  drawCorrespondences();
});

$('corr-clear').addEventListener('click', () => { state.pending = null; drawCorrespondences(); });

$('corr-save').addEventListener('click', async () => {
  const r = await step('Saving correspondences', () => api('PUT', '/api/correspondences', state.corr));
  if (!r) return;
  $('corr-info').textContent = `${r.saved} saved`;
  markDone('correspondences');
});

// ---- 4 model
function showOutputs(o) {
  const d = $('downloads');
  d.replaceChildren('Download: ');
  for (const [label, url] of [['model.glb', o.glb], ['model.obj', o.obj], ['model.vsg', o.vsg],
    ['estimate.json', o.json], ['report', o.report]]) {
    const a = document.createElement('a');
    a.href = url;
    a.textContent = label;
    if (label !== 'report') a.download = label;
    d.append(a, ' ');
  }
  showModel($('viewer'), $('outline'), fresh(o.glb));
}

$('reconstruct').addEventListener('click', async () => {
  const r = await step('Reconstructing', () => api('POST', '/api/reconstruct'));
  if (!r) return;
  const times = Object.entries(r.stages_ms).map(([k, v]) => `${k} ${v} ms`).join(', ');
  $('reconstruct-info').textContent = `${r.structures} structures, ${r.terminals} terminals (${times})`;
  showOutputs(r.outputs);
  markDone('model');
});

function markDone(stepName) {
  const a = document.querySelector(`nav a[data-step=${stepName}]`);
  if (a) a.classList.add('done');
}

async function refresh() {
  const p = await api('GET', '/api/project');
  state.project = p.project;
  state.training = p.training || {};
  state.corr = (p.project && p.project.correspondence) || [];
  const select = $('facade-select');
  const facades = (p.project && p.project.facade) || [];
  select.replaceChildren(...facades.map((f) => new Option(f.image, f.image)));
  document.title = `castellan — ${p.dir}`;
  await showPlan();
  if (facades.length && !facades.some((f) => f.image === state.facade)) await selectFacade(facades[0].image);
  return p;
}

refresh()
  .then((p) => {
    if (p.outputs) showOutputs(p.outputs);
    status(p.project ? `Project ${p.dir}` : `New project in ${p.dir}: upload a plan drawing`);
    document.body.dataset.readyMs = String(Math.round(performance.now()));
    document.body.dataset.ready = 'true';
  })
  .catch((e) => status(e.message, true));
