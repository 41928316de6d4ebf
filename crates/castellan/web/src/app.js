// The `castellan serve` page: plan (upload, cleaning with a brush §5.1.1, labels overlay) →
// façades (upload, training boxes drawn with the mouse, rectification segments to drag §3.1.1,
// façade overlay) → correspondences (click a façade point, then plan point(s)) → reconstruction
// shown in the model viewer. Every change is saved by the server.
import { showModel } from './viewer.js';
import { initPlanFixes } from './plan_fix.js';
import { facadeFix } from './facade_fix.js';
import { setupGothic } from './gothic_fix.js';

const $ = (id) => document.getElementById(id);
const COLOURS = { window: '#00c853', wall: '#d500f9', background: '#ff1744', whole_window: '#00c853' };
const state = {
  project: null, training: {}, facade: null, photos: {}, pending: null, corr: [],
  strokes: [], inkStrokes: [], lines: { horizontal: [], vertical: [] }, version: null,
};

function status(text, error = false) {
  const s = $('status');
  s.textContent = text;
  s.className = error ? 'error' : '';
}

// The run's secret, from the URL castellan serve printed (`/?token=…`). Every API call sends it
// in a header, which a page of another site cannot add; images and downloads use the cookie the
// server set when it served this page.
const TOKEN = new URLSearchParams(window.location.search).get('token') || '';

async function api(method, url, body) {
  const init = { method, headers: { 'x-castellan-token': TOKEN } };
  if (body instanceof FormData) init.body = body;
  else if (body !== undefined) {
    init.body = JSON.stringify(body);
    init.headers['content-type'] = 'application/json';
  }
  // The project's version as this page last saw it: a change made meanwhile elsewhere (another
  // tab, an editor) makes the server refuse the save (412) instead of losing that change.
  if (method !== 'GET' && state.version) init.headers['if-match'] = state.version;
  const res = await fetch(url, init);
  const version = res.headers.get('etag');
  if (version) state.version = version;
  const data = await res.json().catch(() => ({ error: `${res.status} ${res.statusText}` }));
  if (res.status === 403 && !TOKEN) throw new Error('open the URL castellan serve printed (it ends in ?token=…)');
  if (!res.ok) throw new Error(data.error || `${res.status}`);
  return data;
}

// Shows the server's running step: its elapsed time and, when it ran before, a bar measured
// against its last duration.
function showProgress(label, p) {
  const bar = $('progress');
  const secs = (ms) => (ms / 1000).toFixed(1);
  let text = `${label}: ${p.running} ${secs(p.elapsed_ms)} s`;
  if (p.expected_ms) {
    text += ` (last time ${secs(p.expected_ms)} s)`;
    bar.max = p.expected_ms;
    bar.value = Math.min(p.elapsed_ms, 0.99 * p.expected_ms);
  } else bar.removeAttribute('value');
  status(text);
}

// Runs a step, showing the server's progress while it lasts and the outcome after; null on failure.
async function step(label, work) {
  status(`${label}…`);
  const bar = $('progress');
  bar.removeAttribute('value');
  bar.hidden = false;
  let done = false;
  const poll = async () => {
    const p = await api('GET', '/api/progress').catch(() => null);
    if (!done && p && p.running) showProgress(label, p);
  };
  const timer = setInterval(poll, 250);
  poll();
  try {
    const out = await work();
    status(`${label}: done`);
    return out;
  } catch (e) {
    // Shown to the user; callers get null and stop.
    status(`${label}: ${e.message}`, true);
    return null;
  } finally {
    done = true;
    clearInterval(timer);
    bar.hidden = true;
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
let redrawPlan = () => {};
let painting = null;

function drawStrokes(ctx) {
  ctx.lineCap = 'round';
  ctx.lineJoin = 'round';
  // Cleaning strokes paint ink or paper; teaching strokes (the wall ink's) show in colour.
  const teach = state.inkStrokes.map((s) => ({ ...s, colour: s.wall ? 'rgba(220,30,30,0.6)' : 'rgba(30,90,230,0.6)' }));
  for (const s of state.strokes.concat(teach)) {
    const colour = s.colour || (s.ink ? '#000' : '#fff');
    ctx.strokeStyle = colour;
    ctx.fillStyle = colour;
    ctx.lineWidth = 2 * s.radius;
    ctx.beginPath();
    if (s.points.length === 1) {
      ctx.arc(s.points[0][0], s.points[0][1], s.radius, 0, 2 * Math.PI);
      ctx.fill();
    } else {
      ctx.moveTo(...s.points[0]);
      for (const pt of s.points.slice(1)) ctx.lineTo(...pt);
      ctx.stroke();
    }
  }
}

function showStrokeCount(note) {
  $('clean-info').dataset.strokes = String(state.strokes.length);
  $('clean-info').textContent = `${state.strokes.length} strokes (${note})`;
}

async function showPlan() {
  const p = state.project;
  if (!p) return;
  // The binary image of the uploaded drawing, with the saved strokes painted again on it.
  const binary = await loadImage(fresh('/api/plan/binary'));
  redrawPlan = canvasImage($('plan-canvas'), binary, drawStrokes);
  showStrokeCount(p.plan === (state.cleaning && state.cleaning.original) ? 'original drawing' : `saved as ${p.plan}`);
  state.planImage = await loadImage(fresh(`/files/${p.plan}`));
  drawCorrespondences();
}

const brushSize = () => Number($('brush-size').value);
$('brush-size').addEventListener('input', () => { $('brush-size-value').value = String(brushSize()); });

function showInkInfo(note) {
  $('ink-info').dataset.strokes = String(state.inkStrokes.length);
  $('ink-info').textContent = `${state.inkStrokes.length} wall-ink strokes (${note})`;
}

$('plan-canvas').addEventListener('mousedown', (ev) => {
  const brush = document.querySelector('input[name=brush]:checked').value;
  const points = [toImagePixels($('plan-canvas'), ev)];
  if (brush === 'wall' || brush === 'notwall') {
    painting = { wall: brush === 'wall', radius: brushSize() / 2, points };
    state.inkStrokes.push(painting);
  } else {
    painting = { ink: brush === 'ink', radius: brushSize() / 2, points };
    state.strokes.push(painting);
  }
  redrawPlan();
});
$('plan-canvas').addEventListener('mousemove', (ev) => {
  if (!painting) return;
  const pt = toImagePixels($('plan-canvas'), ev);
  const last = painting.points[painting.points.length - 1];
  if (Math.hypot(pt[0] - last[0], pt[1] - last[1]) < 1) return;
  painting.points.push(pt);
  redrawPlan();
});
window.addEventListener('mouseup', () => {
  if (!painting) return;
  painting.points = painting.points.map(([x, y]) => [Math.round(x * 10) / 10, Math.round(y * 10) / 10]);
  if ('wall' in painting) showInkInfo('unsaved'); else showStrokeCount('unsaved');
  painting = null;
});

$('ink-undo').addEventListener('click', () => {
  state.inkStrokes.pop();
  redrawPlan();
  showInkInfo('unsaved');
});

$('ink-save').addEventListener('click', async () => {
  const body = { ink: $('ink-method').value, strokes: state.inkStrokes };
  const r = await step('Saving the wall-ink strokes', () => api('PUT', '/api/plan/ink', body));
  if (!r) return;
  showInkInfo(`saved, walls read by ${r.ink}`);
  await parsePlan();
});

$('clean-undo').addEventListener('click', () => {
  state.strokes.pop();
  redrawPlan();
  showStrokeCount('unsaved');
});

$('clean-reset').addEventListener('click', () => {
  state.strokes = [];
  redrawPlan();
  showStrokeCount('unsaved: Save to go back to the original');
});

async function parsePlan() {
  const r = await step('Parsing the plan', () => api('POST', '/api/plan'));
  if (!r) return;
  const warned = r.warnings.length ? `; ${r.warnings.join('; ')}` : '';
  $('plan-info').textContent = `${r.towers} towers, ${r.faces} regions, ${r.edges} edges in ${r.ms} ms${warned}`;
  $('plan-info').dataset.faces = String(r.faces);
  $('plan-info').dataset.towers = String(r.towers);
  await showOverlay('plan-walls', r.walls);
  await showOverlay('plan-overlay', r.overlay);
  await planFixes.showOverlay(r.overlay);
  markDone('plan');
}

const planFixes = initPlanFixes({ $, api, step, status, fresh, loadImage, canvasImage, toImagePixels, cross, parsePlan });

$('clean-save').addEventListener('click', async () => {
  const r = await step('Saving the cleaned plan', () =>
    api('PUT', '/api/plan/cleaning', { strokes: state.strokes }));
  if (!r) return;
  state.project.plan = r.plan;
  showStrokeCount(`saved as ${r.plan}, ${r.changed_pixels} pixels changed`);
  state.planImage = await loadImage(fresh(r.url));
  drawCorrespondences();
  await parsePlan();
});

$('plan-file').addEventListener('change', async (ev) => {
  const file = ev.target.files[0];
  if (!file) return;
  if (!(await upload('plan', file))) return;
  await refresh().catch((e) => status(e.message, true));
});

$('plan-run').addEventListener('click', parsePlan);

// ---- 2 façades
// Issue 22: the façade tree's corrections (facade_fix.js).
const fixes = facadeFix({ api, step, loadImage, fresh, toImagePixels, facade: () => state.facade });
let redrawPhoto = () => {};
let drag = null;

function boxes() {
  const t = state.training[state.facade] || { classes: {} };
  state.training[state.facade] = t;
  return t.classes;
}

// The list a drawn box of kind `cls` goes to: a class's boxes, or the whole windows (TRAINING.json
// `whole_windows`, issue 21: windows outlined frame and all, whose repeats the search finds).
function listFor(cls) {
  const t = state.training[state.facade];
  if (cls === 'whole_window') return (t.whole_windows ||= []);
  return (boxes()[cls] ||= []);
}

// Every box with its kind, whole windows included.
function allBoxes() {
  const t = state.training[state.facade] || {};
  return [...Object.entries(boxes()), ['whole_window', t.whole_windows || []]];
}

function showBoxCount(note) {
  const n = allBoxes().reduce((a, [, l]) => a + l.length, 0);
  $('boxes-info').dataset.count = String(n);
  $('boxes-info').textContent = `${n} boxes (${note})`;
}

// Issue 21: after each box, the pixel classifier's class probabilities over the photo for the
// boxes drawn so far (saved or not), as ilastik shows them live. A newer request supersedes an
// older one still running.
let previewRequest = 0;
async function showPreview() {
  const name = state.facade;
  const info = $('preview-info');
  const img = $('preview-overlay');
  const classes = boxes();
  info.className = '';
  const windows = (classes.window || []).length + (state.training[name].whole_windows || []).length;
  if (!windows || !(classes.wall || []).length) {
    img.removeAttribute('src');
    img.dataset.loaded = 'false';
    info.textContent = 'Draw a window box and a wall box to see what the classifier learns';
    return;
  }
  const request = ++previewRequest;
  info.textContent = 'Classifying…';
  const res = await fetch(`/api/facades/${encodeURIComponent(name)}/preview`, {
    method: 'POST',
    headers: { 'x-castellan-token': TOKEN, 'content-type': 'application/json' },
    body: JSON.stringify(state.training[name]),
  }).catch((e) => ({ ok: false, statusText: e.message, json: async () => ({}) }));
  if (request !== previewRequest || name !== state.facade) return;
  if (!res.ok) {
    const data = await res.json().catch(() => ({}));
    info.textContent = data.error || res.statusText;
    info.className = 'error';
    return;
  }
  const url = URL.createObjectURL(await res.blob());
  if (img.src.startsWith('blob:')) URL.revokeObjectURL(img.src);
  img.onload = () => { img.dataset.loaded = 'true'; };
  img.src = url;
  const n = allBoxes().reduce((a, [, l]) => a + l.length, 0);
  const repeats = Number(res.headers.get('x-castellan-repeats') || 0);
  info.dataset.repeats = String(repeats);
  info.textContent = `Class probabilities from ${n} boxes (green window, magenta wall, red ` +
    `background; blended where unsure), ${res.headers.get('x-castellan-ms')} ms` +
    (repeats ? `; your whole windows repeat as ${repeats} windows (outlined green)` : '');
}

function drawBoxes(ctx) {
  for (const [cls, list] of allBoxes()) {
    ctx.strokeStyle = COLOURS[cls] || '#000';
    ctx.lineWidth = Math.max(2, ctx.canvas.width / 300);
    // Whole windows dashed, boxes inside a class solid.
    ctx.setLineDash(cls === 'whole_window' ? [10, 5] : []);
    for (const [x0, y0, x1, y1] of list) ctx.strokeRect(x0, y0, x1 - x0, y1 - y0);
  }
  ctx.setLineDash([]);
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
  fixes.select();
  $('facade-select').value = name;
  if (!name) return;
  const img = await loadImage(fresh(`/files/${name}`));
  state.photos[name] = img;
  redrawPhoto = canvasImage($('facade-canvas'), img, drawBoxes);
  showBoxCount('saved');
  showPreview();
  // The façade's saved segments, if any; otherwise the detected ones appear after Rectify.
  const entry = ((state.project && state.project.facade) || []).find((f) => f.image === name);
  state.lines = { horizontal: [], vertical: [] };
  state.selected = null;
  if (entry && entry.lines) {
    state.lines = await api('GET', fresh(`/files/${entry.lines}`)).catch(() => state.lines);
  }
  redrawLines = canvasImage($('lines-canvas'), img, drawLines);
  showLines(entry && entry.lines ? `yours, from ${entry.lines}` : 'Rectify to see the detected ones');
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
    if (x1 - x0 >= 2 && y1 - y0 >= 2) {
      listFor(d.cls).push([x0, y0, x1, y1].map(Math.round));
      showPreview();
    }
  }
  redrawPhoto();
  showBoxCount('unsaved');
});

$('boxes-undo').addEventListener('click', () => {
  const cls = document.querySelector('input[name=class]:checked').value;
  listFor(cls).pop();
  redrawPhoto();
  showBoxCount('unsaved');
  showPreview();
});

$('boxes-save').addEventListener('click', async () => {
  const name = state.facade;
  const r = await step('Saving boxes', () =>
    api('PUT', `/api/facades/${encodeURIComponent(name)}/training`, state.training[name]));
  if (!r) return;
  $('boxes-info').dataset.count = String(r.boxes);
  $('boxes-info').textContent = `${r.boxes} boxes saved to ${r.saved}`;
});

async function rectify() {
  const name = state.facade;
  const r = await step('Rectifying', () => api('POST', `/api/facades/${encodeURIComponent(name)}/rectify`));
  if (!r) return;
  $('facade-info').textContent =
    `${r.horizontal} horizontal, ${r.vertical} vertical segments; ${r.width}×${r.height} in ${r.ms} ms`;
  state.lines = r.lines;
  state.selected = null;
  showLines(r.manual ? 'yours' : 'detected');
  await showOverlay('rectify-overlay', r.overlay);
}

$('facade-rectify').addEventListener('click', rectify);

// ---- 2b rectification segments: drag an end, draw a new one, select and remove one
let redrawLines = () => {};
let lineDrag = null;

function showLines(note) {
  const { horizontal, vertical } = state.lines;
  const info = $('lines-info');
  $('lines-canvas').dataset.segments = JSON.stringify(state.lines);
  info.dataset.horizontal = String(horizontal.length);
  info.dataset.vertical = String(vertical.length);
  info.textContent = `${horizontal.length} horizontal, ${vertical.length} vertical (${note})`;
  redrawLines();
}

function handleSize(canvas) {
  return Math.max(5, canvas.width / 90);
}

function drawLines(ctx) {
  const h = handleSize(ctx.canvas);
  for (const [family, colour] of [['horizontal', '#e53935'], ['vertical', '#1e88e5']]) {
    state.lines[family].forEach((seg, i) => {
      const chosen = state.selected && state.selected.family === family && state.selected.index === i;
      ctx.strokeStyle = chosen ? '#ffd600' : colour;
      ctx.lineWidth = Math.max(2, h / 2.5);
      ctx.beginPath();
      ctx.moveTo(seg[0], seg[1]);
      ctx.lineTo(seg[2], seg[3]);
      ctx.stroke();
      ctx.fillStyle = colour;
      for (const k of [0, 2]) ctx.fillRect(seg[k] - h / 2, seg[k + 1] - h / 2, h, h);
    });
  }
}

function distanceToSegment([px, py], [x0, y0, x1, y1]) {
  const [dx, dy] = [x1 - x0, y1 - y0];
  const len2 = dx * dx + dy * dy;
  const t = len2 ? Math.min(1, Math.max(0, ((px - x0) * dx + (py - y0) * dy) / len2)) : 0;
  return Math.hypot(px - x0 - t * dx, py - y0 - t * dy);
}

// The segment end under the pointer, else the segment under it, else null.
function hitLine(pt, tolerance) {
  let best = null;
  for (const family of ['horizontal', 'vertical']) {
    state.lines[family].forEach((seg, index) => {
      for (const end of [0, 1]) {
        const d = Math.hypot(pt[0] - seg[2 * end], pt[1] - seg[2 * end + 1]);
        if (d <= tolerance && (!best || best.end === undefined || d < best.d)) best = { family, index, end, d };
      }
      const d = distanceToSegment(pt, seg);
      if (d <= tolerance / 2 && !best) best = { family, index, d };
    });
  }
  return best;
}

function setFacadeLines(name, file) {
  const entry = ((state.project && state.project.facade) || []).find((f) => f.image === name);
  if (entry) entry.lines = file;
}

const linesCanvas = $('lines-canvas');
linesCanvas.addEventListener('mousedown', (ev) => {
  const pt = toImagePixels(linesCanvas, ev);
  const hit = hitLine(pt, handleSize(linesCanvas) * 1.5);
  if (hit && hit.end !== undefined) {
    lineDrag = { ...hit, moved: false };
  } else if (hit) {
    state.selected = { family: hit.family, index: hit.index };
    redrawLines();
  } else {
    const family = document.querySelector('input[name=family]:checked').value;
    state.lines[family].push([pt[0], pt[1], pt[0], pt[1]]);
    lineDrag = { family, index: state.lines[family].length - 1, end: 1, fresh: true, moved: false };
  }
});
linesCanvas.addEventListener('mousemove', (ev) => {
  if (!lineDrag) return;
  const [x, y] = toImagePixels(linesCanvas, ev);
  const seg = state.lines[lineDrag.family][lineDrag.index];
  seg[2 * lineDrag.end] = x;
  seg[2 * lineDrag.end + 1] = y;
  lineDrag.moved = true;
  redrawLines();
});
window.addEventListener('mouseup', () => {
  if (!lineDrag) return;
  const d = lineDrag;
  lineDrag = null;
  const list = state.lines[d.family];
  const seg = list[d.index];
  if (d.fresh && Math.hypot(seg[2] - seg[0], seg[3] - seg[1]) < 5) list.splice(d.index, 1);
  else list[d.index] = seg.map((v) => Math.round(v * 10) / 10);
  if (d.moved) showLines('unsaved');
  else redrawLines();
});

$('lines-remove').addEventListener('click', () => {
  const sel = state.selected;
  if (!sel) { status('Click a segment to select it first', true); return; }
  state.lines[sel.family].splice(sel.index, 1);
  state.selected = null;
  showLines('unsaved');
});

$('lines-save').addEventListener('click', async () => {
  const name = state.facade;
  const r = await step('Saving the lines', () =>
    api('PUT', `/api/facades/${encodeURIComponent(name)}/lines`, state.lines));
  if (!r) return;
  setFacadeLines(name, r.saved);
  await rectify();
});

$('lines-auto').addEventListener('click', async () => {
  const name = state.facade;
  const r = await step('Back to automatic lines', () =>
    api('DELETE', `/api/facades/${encodeURIComponent(name)}/lines`));
  if (!r) return;
  setFacadeLines(name, null);
  await rectify();
});

$('facade-run').addEventListener('click', async () => {
  const name = state.facade;
  const r = await step('Façade search', () => api('POST', `/api/facades/${encodeURIComponent(name)}/facade`));
  if (!r) return;
  const warned = (r.warnings || []).length ? `; ${r.warnings.join('; ')}` : '';
  $('facade-info').textContent = `${r.facades} façade(s), ${r.floors} floor(s), ${r.windows} window(s) in ${r.ms} ms${warned}`;
  state.outlines[name] = (r.outlines || []).filter(Boolean);
  drawCorrespondences();
  await showOverlay('facade-overlay', r.overlay);
  markDone('facades');
});

// ---- 3 correspondences
let redrawCorrPhoto = () => {};
state.outlines = {}; // photo name → the façades found, quadrilaterals in photo pixels

// The façades found in the photo, dashed: a correspondence's photo point must fall in one.
function drawOutlines(ctx, quads) {
  ctx.save();
  ctx.strokeStyle = '#00c853';
  ctx.lineWidth = Math.max(2, ctx.canvas.width / 300);
  ctx.setLineDash([ctx.lineWidth * 4, ctx.lineWidth * 3]);
  for (const q of quads) {
    ctx.beginPath();
    q.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    ctx.closePath();
    ctx.stroke();
  }
  ctx.restore();
}

// Inside a convex quadrilateral, whichever way round its corners go.
function inQuad(q, [x, y]) {
  const side = q.map((a, i) => {
    const b = q[(i + 1) % q.length];
    return Math.sign((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]));
  });
  return side.every((s) => s >= 0) || side.every((s) => s <= 0);
}
let redrawCorrPlan = () => {};

function drawCorrespondences() {
  const photo = state.photos[state.facade];
  if (photo) {
    redrawCorrPhoto = canvasImage($('corr-photo'), photo, (ctx) => {
      drawOutlines(ctx, state.outlines[state.facade] || []);
      ctx.canvas.dataset.outlines = JSON.stringify(state.outlines[state.facade] || []);
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
  const point = toImagePixels($('corr-photo'), ev);
  const quads = state.outlines[state.facade];
  // Once the façade search has run, a click outside every façade it found would be refused
  // by the reconstruction: say so here, in the photo the user sees.
  if (quads && !quads.some((q) => inQuad(q, point))) {
    status(`(${point.map((v) => v.toFixed(0)).join(', ')}) is outside the façades found (dashed green): click inside one`, true);
    return;
  }
  state.pending = { facade: state.facade, facade_point: point, plan_points: [] };
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
  for (const [label, url] of [['model.glb', o.glb], ['model.obj', o.obj],
    ['model.city.json', o.cityjson], ['model.ifc', o.ifc], ['model.vsg', o.vsg],
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
  // What looks implausible, as the report and the command line say it.
  $('reconstruct-warnings').replaceChildren(...(r.warnings || []).map((w) => {
    const li = document.createElement('li');
    li.textContent = `Warning: ${w}`;
    return li;
  }));
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
  state.cleaning = p.cleaning;
  state.strokes = (p.cleaning && p.cleaning.strokes) || [];
  state.inkStrokes = (p.project && p.project.ink_stroke) || [];
  $('ink-method').value = (p.project && p.project.ink) || 'learned';
  if (p.project) showInkInfo('saved');
  const select = $('facade-select');
  const facades = (p.project && p.project.facade) || [];
  select.replaceChildren(...facades.map((f) => new Option(f.image, f.image)));
  document.title = `castellan — ${p.dir}`;
  gothic.show(p.project);
  await showPlan();
  await planFixes.load(p.project);
  // The last parse's overlays, as they were left (the page may have been reloaded).
  if (p.project && p.plan_overlays) {
    await showOverlay('plan-walls', p.plan_overlays.walls);
    await showOverlay('plan-overlay', p.plan_overlays.labels);
    await planFixes.showOverlay(p.plan_overlays.labels).catch(() => {});
  }
  if (facades.length && !facades.some((f) => f.image === state.facade)) await selectFacade(facades[0].image);
  return p;
}

// The Gothic step (gothic_fix.js), sharing the page's API calls and project version.
const gothic = setupGothic({ api, step, upload, refresh });

refresh()
  .then((p) => {
    if (p.outputs) showOutputs(p.outputs);
    status(p.project ? `Project ${p.dir}` : `New project in ${p.dir}: upload a plan drawing`);
    document.body.dataset.readyMs = String(Math.round(performance.now()));
    document.body.dataset.ready = 'true';
  })
  .catch((e) => status(e.message, true));
