#!/usr/bin/env node
// Converts the URDF visual meshes of the example-robot-data 6.0.0 wheel (COLLADA .dae, about
// 17 MB, not vendored) into one small glTF binary per mesh for the page: welded, simplified within
// a fixed error, quantised and meshopt-compressed, colours kept. Writes web/public/robots/<robot>/
// (the .glb files, robot.json with the kinematic tree and each link's visuals, the licence).
//
// Usage: node scripts/robot-meshes/convert.mjs [--wheel PATH] [--out DIR] [--robot panda|ur5]...
//   --wheel: a downloaded wheel (its sha256 is checked); default `pip download` into a temp dir.
//   --out: the folder that gets one subfolder per robot (default web/public/robots).
// The output is deterministic: the same wheel gives the same bytes.
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DOMParser } from '@xmldom/xmldom';
import { unzipSync } from 'fflate';
import * as THREE from 'three';
import { ColladaLoader } from 'three/examples/jsm/loaders/ColladaLoader.js';
import { Document, Logger, NodeIO } from '@gltf-transform/core';
import { EXTMeshoptCompression, KHRMeshQuantization } from '@gltf-transform/extensions';
import { dedup, join as joinPrimitives, meshopt, prune, simplify } from '@gltf-transform/functions';
import { MeshoptEncoder, MeshoptSimplifier } from 'meshoptimizer';

const root = fileURLToPath(new URL('../..', import.meta.url));
const WHEEL = 'example_robot_data-6.0.0-0-py3-none-any.whl';
const WHEEL_SHA256 = '424092a8093411ac2cd4ccc0572382bfc6b5eb4833aa984ef5e671dd67cd0a6e';
const SHARE = 'cmeel.prefix/share/example-robot-data/';

/**
 * The robots converted: the URDF read for the kinematic tree (the Panda's vendored copy, which the
 * simulator reads too; the UR5's from the wheel), the visual meshes' folder in the wheel, the
 * licence copied beside them, and how far simplification may move the surface (m).
 */
const ROBOTS = {
  panda: {
    urdf: { repo: 'robots/example-robot-data/robots/panda_description/urdf/panda.urdf' },
    meshes: 'robots/panda_description/meshes/visual/',
    licence: 'robots/example-robot-data/robots/panda_description/LICENSE',
    maxError: 0.0002,
  },
  ur5: {
    urdf: { wheel: 'robots/ur_description/urdf/ur5_robot.urdf' },
    meshes: 'robots/ur_description/meshes/ur5/visual/',
    licence: 'robots/example-robot-data/LICENSE',
    maxError: 0.0002,
  },
};

function fail(msg) {
  console.error(`robot-meshes: ${msg}`);
  process.exit(1);
}

function args() {
  const a = process.argv.slice(2);
  const o = { wheel: null, out: join(root, 'web/public/robots'), robots: [] };
  for (let i = 0; i < a.length; i++) {
    const v = a[i + 1];
    if (a[i] === '--wheel' && v) (o.wheel = v), i++;
    else if (a[i] === '--out' && v) (o.out = v), i++;
    else if (a[i] === '--robot' && v) {
      if (!(v in ROBOTS)) fail(`--robot ${v}: expected one of ${Object.keys(ROBOTS).join(', ')}`);
      o.robots.push(v);
      i++;
    } else fail(`unknown argument ${a[i]} (usage: convert.mjs [--wheel PATH] [--out DIR] [--robot NAME]...)`);
  }
  if (!o.robots.length) o.robots = Object.keys(ROBOTS);
  return o;
}

/** The wheel's bytes, checked against the pinned sha256 (downloaded with pip when no path is given). */
function wheelBytes(path) {
  let tmp = null;
  if (!path) {
    tmp = mkdtempSync(join(tmpdir(), 'robot-meshes-'));
    console.log(`pip download example-robot-data==6.0.0 into ${tmp}`);
    try {
      execFileSync('pip', ['download', 'example-robot-data==6.0.0', '--no-deps', '--only-binary', ':all:', '-d', tmp], { stdio: 'inherit' });
    } catch (e) {
      fail(`pip download failed (${e.message}); pass a downloaded wheel with --wheel PATH`);
    }
    path = join(tmp, WHEEL);
  }
  let bytes;
  try {
    bytes = readFileSync(path);
  } catch (e) {
    fail(`cannot read the wheel ${path}: ${e.message}`);
  }
  if (tmp) rmSync(tmp, { recursive: true, force: true });
  const sha = createHash('sha256').update(bytes).digest('hex');
  if (sha !== WHEEL_SHA256) fail(`${path}: sha256 ${sha}, expected ${WHEEL_SHA256} (${WHEEL})`);
  return bytes;
}

// ---- URDF → robot.json ----

const nums = (s, n, where) => {
  const v = (s ?? Array(n).fill('0').join(' ')).trim().split(/\s+/).map(Number);
  if (v.length !== n || v.some((x) => !Number.isFinite(x))) fail(`${where}: expected ${n} numbers, got "${s}"`);
  return v;
};

/** The `<origin>` child of `el` as { xyz, rpy } (zeros when absent). */
function origin(el, where) {
  const o = childElements(el, 'origin')[0];
  return { xyz: nums(o?.getAttribute('xyz') || null, 3, `${where} origin xyz`), rpy: nums(o?.getAttribute('rpy') || null, 3, `${where} origin rpy`) };
}

function childElements(el, tag) {
  const out = [];
  for (let c = el.firstChild; c; c = c.nextSibling) if (c.nodeType === 1 && c.nodeName === tag) out.push(c);
  return out;
}

/**
 * The kinematic tree of a URDF: its links with their mesh visuals (file → the .glb written here,
 * the visual's origin and scale), and its joints (type, parent, child, origin, axis, limits,
 * mimic), in file order.
 */
function urdfManifest(text, file) {
  const doc = new DOMParser({ onError: (level, msg) => level !== 'warning' && fail(`${file}: ${msg}`) }).parseFromString(text, 'text/xml');
  const robot = doc.documentElement;
  if (robot?.nodeName !== 'robot') fail(`${file}: expected a <robot> root element`);
  const links = [];
  const meshes = new Set();
  for (const l of childElements(robot, 'link')) {
    const name = l.getAttribute('name');
    const visuals = [];
    for (const v of childElements(l, 'visual')) {
      const mesh = childElements(childElements(v, 'geometry')[0] ?? v, 'mesh')[0];
      if (!mesh) continue;
      const src = basename(mesh.getAttribute('filename') ?? '');
      if (!src.endsWith('.dae')) fail(`${file}: link ${name}: visual mesh ${src} is not a .dae`);
      meshes.add(src);
      visuals.push({ file: src.replace(/\.dae$/, '.glb'), ...origin(v, `${file}: link ${name} visual`), scale: nums(mesh.getAttribute('scale') || '1 1 1', 3, `${file}: link ${name} mesh scale`) });
    }
    links.push({ name, visuals });
  }
  const joints = childElements(robot, 'joint').map((j) => {
    const name = j.getAttribute('name');
    const where = `${file}: joint ${name}`;
    const limit = childElements(j, 'limit')[0];
    const mimic = childElements(j, 'mimic')[0];
    return {
      name,
      type: j.getAttribute('type'),
      parent: childElements(j, 'parent')[0]?.getAttribute('link'),
      child: childElements(j, 'child')[0]?.getAttribute('link'),
      ...origin(j, where),
      axis: nums(childElements(j, 'axis')[0]?.getAttribute('xyz') || '1 0 0', 3, `${where} axis`),
      ...(limit ? { lower: Number(limit.getAttribute('lower') ?? 0), upper: Number(limit.getAttribute('upper') ?? 0) } : {}),
      ...(mimic ? { mimic: { joint: mimic.getAttribute('joint'), multiplier: Number(mimic.getAttribute('multiplier') ?? 1), offset: Number(mimic.getAttribute('offset') ?? 0) } } : {}),
    };
  });
  for (const j of joints) if (!j.parent || !j.child) fail(`${file}: joint ${j.name}: missing <parent> or <child>`);
  return { name: robot.getAttribute('name'), links, joints, meshes: [...meshes].sort() };
}

// ---- COLLADA → glb ----

// three's ColladaLoader reads XML through the browser's DOMParser and Node constants.
globalThis.DOMParser = DOMParser;
globalThis.Node ??= { ELEMENT_NODE: 1, TEXT_NODE: 3 };

/**
 * The triangles of a COLLADA file in its own frame (z up, metres: the loader's y-up turn is
 * undone, its unit scale kept), one group per colour.
 */
function colladaTriangles(text, file) {
  const warn = console.warn;
  const log = console.log;
  // The loader logs the file version and warns that it turns z-up assets to y-up (undone below).
  const debug = console.debug;
  console.warn = console.log = console.debug = () => {};
  let parsed;
  try {
    parsed = new ColladaLoader().parse(text, '');
  } finally {
    console.warn = warn;
    console.log = log;
    console.debug = debug;
  }
  if (!parsed) fail(`${file}: not a COLLADA document`);
  const scene = parsed.scene;
  scene.rotation.set(0, 0, 0);
  scene.updateMatrixWorld(true);
  /** colour key → { color: [r,g,b,a] linear, positions: number[], normals: number[] } */
  const groups = new Map();
  scene.traverse((o) => {
    if (!o.isMesh) return;
    const g = o.geometry.index ? o.geometry.toNonIndexed() : o.geometry;
    const pos = g.getAttribute('position');
    const nor = g.getAttribute('normal');
    if (!pos || !nor) fail(`${file}: mesh ${o.name} has no positions or normals`);
    const normalMatrix = new THREE.Matrix3().getNormalMatrix(o.matrixWorld);
    const mats = Array.isArray(o.material) ? o.material : [o.material];
    const ranges = g.groups.length ? g.groups : [{ start: 0, count: pos.count, materialIndex: 0 }];
    const p = new THREE.Vector3();
    const n = new THREE.Vector3();
    for (const r of ranges) {
      const m = mats[r.materialIndex ?? 0] ?? mats[0];
      const color = [m.color.r, m.color.g, m.color.b, m.opacity ?? 1].map((c) => Math.round(c * 1e4) / 1e4);
      const key = color.join(',');
      let grp = groups.get(key);
      if (!grp) groups.set(key, (grp = { color, positions: [], normals: [] }));
      for (let i = r.start; i < r.start + r.count; i++) {
        p.fromBufferAttribute(pos, i).applyMatrix4(o.matrixWorld);
        n.fromBufferAttribute(nor, i).applyMatrix3(normalMatrix).normalize();
        grp.positions.push(p.x, p.y, p.z);
        grp.normals.push(n.x, n.y, n.z);
      }
    }
  });
  if (!groups.size) fail(`${file}: no triangles`);
  return [...groups.values()].sort((a, b) => (a.color.join(',') < b.color.join(',') ? -1 : 1));
}

/** Faces meeting at more than this angle keep a hard edge; smoother ones share normals. */
const CREASE = (35 * Math.PI) / 180;

/**
 * An indexed mesh of a triangle soup: corners at the same point (to 1 µm) become one vertex per
 * smoothing group, whose normal is the area-weighted mean of the faces around the point within
 * `crease` of each other. The source meshes are flat-shaded (one normal per face), which leaves
 * nothing to weld or simplify; smooth normals with hard creases also draw the castings as they are.
 */
function creasedMesh(soup, crease) {
  const corners = soup.length / 3;
  const point = new Uint32Array(corners);
  const keys = new Map();
  const points = [];
  for (let c = 0; c < corners; c++) {
    const key = `${Math.round(soup[3 * c] * 1e6)},${Math.round(soup[3 * c + 1] * 1e6)},${Math.round(soup[3 * c + 2] * 1e6)}`;
    let i = keys.get(key);
    if (i === undefined) {
      i = points.length / 3;
      keys.set(key, i);
      points.push(soup[3 * c], soup[3 * c + 1], soup[3 * c + 2]);
    }
    point[c] = i;
  }
  // Area-weighted face normals (the cross product's length is twice the area); degenerate faces go.
  const faces = [];
  const fn = [];
  const a = new THREE.Vector3();
  const b = new THREE.Vector3();
  const d = new THREE.Vector3();
  for (let f = 0; f < corners / 3; f++) {
    const [i, j, k] = [point[3 * f], point[3 * f + 1], point[3 * f + 2]];
    if (i === j || j === k || i === k) continue;
    a.fromArray(points, 3 * i);
    b.fromArray(points, 3 * j).sub(a);
    d.fromArray(points, 3 * k).sub(a);
    const n = b.cross(d);
    if (n.lengthSq() < 1e-20) continue;
    faces.push(i, j, k);
    fn.push(n.x, n.y, n.z);
  }
  const around = Array.from({ length: points.length / 3 }, () => []);
  for (let f = 0; f < faces.length / 3; f++) for (let k = 0; k < 3; k++) around[faces[3 * f + k]].push(f);
  const unit = fn.map((_, i) => i).filter((i) => i % 3 === 0).map((i) => new THREE.Vector3(fn[i], fn[i + 1], fn[i + 2]).normalize());
  const cos = Math.cos(crease);
  const out = { positions: [], normals: [], indices: [] };
  const vertex = new Map();
  const n = new THREE.Vector3();
  for (let f = 0; f < faces.length / 3; f++) {
    for (let k = 0; k < 3; k++) {
      const p = faces[3 * f + k];
      n.set(0, 0, 0);
      for (const g of around[p]) if (unit[g].dot(unit[f]) >= cos) n.x += fn[3 * g], n.y += fn[3 * g + 1], n.z += fn[3 * g + 2];
      n.normalize();
      const key = `${p}:${Math.round(n.x * 1e4)},${Math.round(n.y * 1e4)},${Math.round(n.z * 1e4)}`;
      let v = vertex.get(key);
      if (v === undefined) {
        v = out.positions.length / 3;
        vertex.set(key, v);
        out.positions.push(points[3 * p], points[3 * p + 1], points[3 * p + 2]);
        out.normals.push(n.x, n.y, n.z);
      }
      out.indices.push(v);
    }
  }
  return { positions: new Float32Array(out.positions), normals: new Float32Array(out.normals), indices: new Uint32Array(out.indices) };
}

/** A compressed glb of one mesh: its colour groups as primitives of one node. */
async function meshGlb(name, groups, maxError) {
  const doc = new Document().setLogger(new Logger(Logger.Verbosity.WARN));
  doc.createExtension(KHRMeshQuantization);
  const buffer = doc.createBuffer();
  const mesh = doc.createMesh(name);
  let triangles = 0;
  groups.forEach((g, i) => {
    const material = doc
      .createMaterial(`${name}-${i}`)
      .setBaseColorFactor(g.color)
      .setMetallicFactor(0)
      .setRoughnessFactor(0.55);
    if (g.color[3] < 1) material.setAlphaMode('BLEND');
    const v = creasedMesh(g.positions, CREASE);
    const prim = doc
      .createPrimitive()
      .setMaterial(material)
      .setIndices(doc.createAccessor().setType('SCALAR').setArray(v.indices).setBuffer(buffer))
      .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(v.positions).setBuffer(buffer))
      .setAttribute('NORMAL', doc.createAccessor().setType('VEC3').setArray(v.normals).setBuffer(buffer));
    mesh.addPrimitive(prim);
    triangles += g.positions.length / 9;
  });
  doc.createScene(name).addChild(doc.createNode(name).setMesh(mesh));
  // simplify's error is relative to the mesh's radius: the same surface tolerance for every link.
  const radius = meshRadius(groups);
  await doc.transform(
    dedup(),
    joinPrimitives(),
    simplify({ simplifier: MeshoptSimplifier, ratio: 0, error: maxError / radius }),
    meshopt({ encoder: MeshoptEncoder, level: 'high', quantizePosition: 14, quantizeNormal: 8 }),
    prune(),
  );
  let after = 0;
  for (const p of mesh.listPrimitives()) after += p.getIndices().getCount() / 3;
  const io = new NodeIO().registerExtensions([EXTMeshoptCompression, KHRMeshQuantization]).registerDependencies({ 'meshopt.encoder': MeshoptEncoder });
  return { glb: await io.writeBinary(doc), triangles, after };
}

function meshRadius(groups) {
  const box = new THREE.Box3();
  const v = new THREE.Vector3();
  for (const g of groups) for (let i = 0; i < g.positions.length; i += 3) box.expandByPoint(v.fromArray(g.positions, i));
  return Math.max(1e-6, box.getSize(v).length() / 2);
}

// ---- main ----

const opts = args();
const zip = unzipSync(wheelBytes(opts.wheel));
const fromWheel = (path) => {
  const b = zip[SHARE + path];
  if (!b) fail(`${WHEEL}: no ${SHARE + path}`);
  return b;
};
await MeshoptEncoder.ready;
await MeshoptSimplifier.ready;
const td = new TextDecoder();
for (const robot of opts.robots) {
  const r = ROBOTS[robot];
  const urdfFile = r.urdf.repo ? join(root, r.urdf.repo) : r.urdf.wheel;
  const urdfText = r.urdf.repo ? readFileSync(urdfFile, 'utf8') : td.decode(fromWheel(r.urdf.wheel));
  const manifest = urdfManifest(urdfText, r.urdf.repo ?? `${WHEEL}: ${r.urdf.wheel}`);
  const out = join(opts.out, robot);
  mkdirSync(out, { recursive: true });
  for (const f of readdirSync(out)) if (f.endsWith('.glb')) rmSync(join(out, f));
  let daeBytes = 0;
  let glbBytes = 0;
  const files = {};
  for (const dae of manifest.meshes) {
    const bytes = fromWheel(r.meshes + dae);
    const { glb, triangles, after } = await meshGlb(dae.replace(/\.dae$/, ''), colladaTriangles(td.decode(bytes), dae), r.maxError);
    const name = dae.replace(/\.dae$/, '.glb');
    writeFileSync(join(out, name), glb);
    daeBytes += bytes.length;
    glbBytes += glb.length;
    files[name] = { bytes: glb.length, triangles: after, sourceTriangles: triangles };
    console.log(`${robot}/${name}: ${dae} ${(bytes.length / 1024).toFixed(0)} KiB, ${triangles} triangles → ${(glb.length / 1024).toFixed(1)} KiB, ${after} triangles`);
  }
  const { meshes, ...tree } = manifest;
  const json = {
    source: `${WHEEL} (sha256 ${WHEEL_SHA256}), ${SHARE}${r.meshes}; tree from ${r.urdf.repo ?? SHARE + r.urdf.wheel}`,
    frames: 'mesh coordinates are the URDF link frames (z up, metres), not glTF y-up',
    ...tree,
    files,
  };
  // Number triples on one line each: the file stays readable.
  const text = JSON.stringify(json, null, 1).replace(/\[\s*(-?[\d.e+-]+),\s*(-?[\d.e+-]+),\s*(-?[\d.e+-]+)\s*\]/g, '[$1, $2, $3]');
  writeFileSync(join(out, 'robot.json'), `${text}\n`);
  writeFileSync(join(out, 'LICENSE'), readFileSync(join(root, r.licence)));
  console.log(`${robot}: ${meshes.length} meshes, COLLADA ${(daeBytes / 1024).toFixed(0)} KiB → glb ${(glbBytes / 1024).toFixed(1)} KiB`);
}
