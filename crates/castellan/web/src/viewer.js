// castellan's model viewer: a glTF model, either embedded in the page (base64, so the report
// opens from disk with no server and no network) or fetched by URL (`castellan serve`), with
// orbit controls and an outline to hide or show each structure and each kind of terminal shape,
// and to peel the walls away (§1.8: hide every wall, or cut the model at a height) to see inside.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

function decode(base64) {
  const bin = atob(base64.trim());
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes.buffer;
}

// The structure a node belongs to: the child of the root it descends from.
function structureOf(node, root) {
  let n = node;
  while (n.parent && n.parent !== root) n = n.parent;
  return n;
}

function checkbox(list, group, label, count, onChange) {
  const row = document.createElement('label');
  row.dataset.group = group;
  row.style.display = 'block';
  const box = document.createElement('input');
  box.type = 'checkbox';
  box.checked = true;
  box.addEventListener('change', () => onChange(box.checked));
  row.append(box, ` ${label} (${count})`);
  list.append(row);
}

// The VSG symbol of a node: three.js keeps the glTF name in userData.name.
function symbolOf(o) {
  let n = o;
  while (n && !(n.userData && n.userData.name)) n = n.parent;
  return (n && n.userData.name) || o.name || 'shape';
}

function fmt(v) {
  return typeof v === 'number' ? (Math.round(v * 1000) / 1000).toString() : String(v);
}

// The clicked part: its symbol, shape, parameters and exact volume (the glTF extras VSG
// writes), and the provenance of its structure's parameters from estimate.json when known.
function describe(panel, mesh, structureName, estimate) {
  const d = mesh.userData || {};
  const rows = [
    ['symbol', symbolOf(mesh)],
    ['structure', structureName],
    ['shape', d.shapeType || '—'],
    ['parameters', (d.params || []).map(fmt).join(', ') || '—'],
    ['volume', d.volume === undefined ? '—' : fmt(d.volume)],
    ['rule line', d.ruleLine === undefined ? '—' : String(d.ruleLine)],
  ];
  const s = estimate && (estimate.structures || []).find((x) => x.id === structureName);
  if (s) {
    rows.push(['label', s.label], ['height', fmt(s.height)]);
    for (const [k, p] of Object.entries(s.provenance || {})) {
      const err = p.fit_error === undefined ? '' : ` (error ${fmt(p.fit_error)} px)`;
      rows.push([k, `${p.image}: ${p.step}${err}`]);
    }
  }
  const table = document.createElement('table');
  for (const [k, v] of rows) {
    const tr = document.createElement('tr');
    const th = document.createElement('th');
    const td = document.createElement('td');
    th.textContent = k;
    td.textContent = v;
    tr.append(th, td);
    table.append(tr);
  }
  panel.replaceChildren(table);
  panel.dataset.symbol = symbolOf(mesh);
}

// Shows a model in `container` (emptied first) with its outline in `outline` (optional).
// `source` is the glb's bytes (ArrayBuffer) or its URL; `estimate` (optional) is estimate.json,
// fetched beside a URL source when not given.
export function showModel(container, outline, source, estimate) {
  container.replaceChildren();
  if (outline) outline.replaceChildren();
  container.dataset.ready = 'false';
  const width = container.clientWidth || 800;
  const height = container.clientHeight || 500;
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(width, height);
  container.append(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xeef1f5);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a7f70, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 2, 1.5);
  scene.add(sun);
  const camera = new THREE.PerspectiveCamera(45, width / height, 0.01, 1e7);
  const controls = new OrbitControls(camera, renderer.domElement);
  const render = () => renderer.render(scene, camera);
  controls.addEventListener('change', render);

  const loaded = (gltf) => {
    const model = gltf.scene;
    scene.add(model);
    const box = new THREE.Box3().setFromObject(model);
    const size = box.getSize(new THREE.Vector3()).length() || 1;
    const centre = box.getCenter(new THREE.Vector3());
    camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.5, 0.8).multiplyScalar(size));
    camera.near = size / 1000;
    camera.far = size * 100;
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
    // The glTF root is the axiom; its children are the structures.
    const root = model.children.length === 1 ? model.children[0] : model;
    const structures = new Map();
    const kinds = new Map();
    model.traverse((o) => {
      if (!o.isMesh) return;
      // Keyed by name: a structure's parts that are siblings (a gable roof's two slopes) are
      // one entry.
      // three.js makes node names unique (`hall1Roof_1`); userData.name keeps the glTF one.
      const top = structureOf(o, root);
      const s = ((top.userData && top.userData.name) || top.name || 'structure').replace(/Site$/, '');
      // The glTF node name is the VSG symbol (three.js keeps it in userData.name); imported
      // symbols carry their namespace (`tower1.masonry`), grouped here by the symbol alone.
      let named = o;
      while (named && !(named.userData && named.userData.name)) named = named.parent;
      const kind = ((named && named.userData.name) || o.name || 'shape').split('.').pop();
      if (!structures.has(s)) structures.set(s, []);
      structures.get(s).push(o);
      if (!kinds.has(kind)) kinds.set(kind, []);
      kinds.get(kind).push(o);
    });
    // Click (not drag) a part to see what it is and where its numbers came from.
    const panel = document.createElement('div');
    panel.className = 'castellan-part';
    panel.textContent = 'Click a part to see its parameters, volume and provenance.';
    if (outline) outline.prepend(panel);
    let info = estimate;
    if (!info && typeof source === 'string') {
      fetch(new URL('estimate.json', new URL(source, window.location.href)))
        .then((r) => (r.ok ? r.json() : null))
        .then((j) => {
          info = j;
        })
        .catch(() => {});
    }
    const ray = new THREE.Raycaster();
    let down = null;
    renderer.domElement.addEventListener('pointerdown', (ev) => {
      down = [ev.clientX, ev.clientY];
    });
    renderer.domElement.addEventListener('pointerup', (ev) => {
      if (!down || Math.hypot(ev.clientX - down[0], ev.clientY - down[1]) > 4) return;
      const r = renderer.domElement.getBoundingClientRect();
      const ndc = new THREE.Vector2(
        ((ev.clientX - r.left) / r.width) * 2 - 1,
        -((ev.clientY - r.top) / r.height) * 2 + 1,
      );
      ray.setFromCamera(ndc, camera);
      const hit = ray.intersectObject(model, true).find((h) => h.object.isMesh && h.object.visible);
      if (!hit) return;
      const top = structureOf(hit.object, root);
      const name = ((top.userData && top.userData.name) || top.name || '').replace(/Site$/, '');
      describe(panel, hit.object, name, info);
    });
    const hidden = new Set();
    // Walls are the parts whose symbol or structure is named a wall (keep1Wall_S, tower1Wall,
    // the curtain wall's segments): peeling them leaves floors, roofs and what is inside.
    const walls = new Set();
    model.traverse((o) => {
      if (!o.isMesh) return;
      for (let n = o; n && n !== root; n = n.parent) {
        if (/wall/i.test((n.userData && n.userData.name) || n.name || '')) walls.add(o);
      }
    });
    let peeled = false;
    const apply = () => {
      let visible = 0;
      model.traverse((o) => {
        if (!o.isMesh) return;
        o.visible = !hidden.has(o) && !(peeled && walls.has(o));
        visible += o.visible ? 1 : 0;
      });
      container.dataset.visibleMeshes = String(visible);
      render();
    };
    // A horizontal cut: everything above the plane is clipped away, so rooms show from above.
    renderer.localClippingEnabled = true;
    const cut = new THREE.Plane(new THREE.Vector3(0, -1, 0), box.max.y);
    // Walls seen at a grazing angle or from afar cover many texels per pixel: trilinear
    // mipmaps (the glb's sampler asks for them; set here too for files that do not) and the
    // GPU's anisotropic filtering keep tiled stone from turning into moiré and static.
    const anisotropy = renderer.capabilities.getMaxAnisotropy();
    model.traverse((o) => {
      if (!o.isMesh) return;
      for (const m of Array.isArray(o.material) ? o.material : [o.material]) {
        m.clippingPlanes = [cut];
        // The inside faces of a cut wall show instead of a hole.
        m.side = THREE.DoubleSide;
        if (m.map) {
          m.map.generateMipmaps = true;
          m.map.minFilter = THREE.LinearMipmapLinearFilter;
          m.map.magFilter = THREE.LinearFilter;
          m.map.anisotropy = anisotropy;
          m.map.needsUpdate = true;
        }
      }
    });
    const setCut = (percent) => {
      cut.constant = box.min.y + ((box.max.y - box.min.y) * percent) / 100 + (percent >= 100 ? size : 0);
      container.dataset.cut = String(percent);
      render();
    };
    const toggle = (meshes) => (on) => {
      for (const m of meshes) {
        if (on) hidden.delete(m);
        else hidden.add(m);
      }
      apply();
    };
    if (outline) {
      const peel = document.createElement('div');
      peel.className = 'peel';
      const peelRow = document.createElement('label');
      peelRow.style.display = 'block';
      const peelBox = document.createElement('input');
      peelBox.type = 'checkbox';
      peelBox.dataset.peel = 'walls';
      peelBox.addEventListener('change', () => {
        peeled = peelBox.checked;
        apply();
      });
      peelRow.append(peelBox, ` Peel walls (${walls.size} parts)`);
      const cutRow = document.createElement('label');
      cutRow.style.display = 'block';
      const cutValue = document.createElement('span');
      cutValue.textContent = '100 %';
      const cutSlider = document.createElement('input');
      cutSlider.type = 'range';
      cutSlider.min = '0';
      cutSlider.max = '100';
      cutSlider.value = '100';
      cutSlider.dataset.cut = 'height';
      cutSlider.addEventListener('input', () => {
        cutValue.textContent = `${cutSlider.value} %`;
        setCut(Number(cutSlider.value));
      });
      cutRow.append('Cut height ', cutValue, cutSlider);
      peel.append(peelRow, cutRow);
      outline.append(peel);
      const h1 = document.createElement('b');
      h1.textContent = 'Structures';
      outline.append(h1);
      for (const [s, meshes] of structures) {
        checkbox(outline, 'structure', s, meshes.length, toggle(meshes));
      }
      const h2 = document.createElement('b');
      h2.textContent = 'Shapes by symbol';
      outline.append(h2);
      for (const [k, meshes] of [...kinds].sort((a, b) => a[0].localeCompare(b[0]))) {
        checkbox(outline, 'symbol', k, meshes.length, toggle(meshes));
      }
    }
    container.dataset.meshes = String(structures.size ? [...structures.values()].flat().length : 0);
    container.dataset.structures = String(structures.size);
    container.dataset.walls = String(walls.size);
    setCut(100);
    apply();
    container.dataset.ready = 'true';
  };
  const failed = (err) => {
    container.dataset.ready = 'error';
    container.textContent = `The model could not be shown: ${err.message || err}`;
  };
  if (typeof source === 'string') new GLTFLoader().load(source, loaded, undefined, failed);
  else new GLTFLoader().parse(source, '', loaded, failed);
  // Frame rate probe for tests: renders `n` frames and reports frames per second.
  window.castellanFps = (n = 60) => new Promise((resolve) => {
    const t0 = performance.now();
    let k = 0;
    const step = () => {
      controls.autoRotate = true;
      controls.update();
      render();
      if (++k < n) requestAnimationFrame(step);
      else resolve((1000 * n) / (performance.now() - t0));
    };
    requestAnimationFrame(step);
  });
}

// The report: the model embedded in a script element.
function start() {
  const data = document.getElementById('castellan-model');
  const container = document.getElementById('viewer');
  if (!data || !container) return;
  const est = document.getElementById('castellan-estimate');
  const estimate = est ? JSON.parse(est.textContent) : undefined;
  showModel(container, document.getElementById('outline'), decode(data.textContent), estimate);
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
else start();
