/**
 * The three.js objects the 3-D view is made of, built from snapshot data: the room (lights, floor,
 * grid), bodies (labelled blocks, tables, the shelf, the hook), region patches with their names;
 * and what goes with them: poses, freeing an object's GPU resources, whether WebGL runs in software.
 */
import * as THREE from 'three';
import type { BodySnapshot, PoseSnapshot, WorldSnapshot } from 'logic-lfd';

/** Places an object at a snapshot's pose. */
export function applyPose(o: THREE.Object3D, p: PoseSnapshot): void {
  o.position.set(p.position[0], p.position[1], p.position[2]);
  o.quaternion.set(p.quaternion[0], p.quaternion[1], p.quaternion[2], p.quaternion[3]);
}

/** A block's face: its colour with its name in large letters. */
function labelTexture(text: string, color: string): THREE.CanvasTexture {
  const c = document.createElement('canvas');
  c.width = c.height = 128;
  const g = c.getContext('2d')!;
  g.fillStyle = color;
  g.fillRect(0, 0, 128, 128);
  g.strokeStyle = 'rgba(0,0,0,0.25)';
  g.lineWidth = 6;
  g.strokeRect(3, 3, 122, 122);
  const dark = luminance(color) > 0.55;
  g.fillStyle = dark ? '#111' : '#fff';
  g.font = 'bold 72px system-ui, sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text.toUpperCase().slice(0, 3), 64, 70);
  const t = new THREE.CanvasTexture(c);
  t.colorSpace = THREE.SRGBColorSpace;
  t.anisotropy = 4;
  return t;
}

/** A region's name on a translucent dark band. */
function textTexture(text: string): THREE.CanvasTexture {
  const c = document.createElement('canvas');
  c.width = 256;
  c.height = 64;
  const g = c.getContext('2d')!;
  g.font = '600 30px system-ui, sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillStyle = 'rgba(20, 23, 28, 0.75)';
  g.fillText(text, 128, 32);
  const t = new THREE.CanvasTexture(c);
  t.colorSpace = THREE.SRGBColorSpace;
  return t;
}

/** Whether WebGL is rasterised on the CPU (SwiftShader, llvmpipe). */
export function isSoftwareRenderer(): boolean {
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    if (!gl) return true;
    const ext = gl.getExtension('WEBGL_debug_renderer_info');
    const name = String(ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER));
    gl.getExtension('WEBGL_lose_context')?.loseContext();
    return /swiftshader|llvmpipe|software/i.test(name);
  } catch {
    return false;
  }
}

/**
 * Frees the GPU resources of an object and its children (geometries, materials, their textures),
 * except those in `shared`, which outlive it. three.js keeps them until `dispose()` is called, so
 * every mesh the view drops goes through here (the page soak test checks the memory stays flat).
 */
export function disposeObject(o: THREE.Object3D, shared: ReadonlySet<unknown> = new Set()): void {
  o.traverse((c) => {
    const m = c as THREE.Mesh | THREE.Line | THREE.Sprite;
    // (Every Sprite shares one module-level geometry inside three.js: never dispose it.)
    if (!(c instanceof THREE.Sprite) && 'geometry' in m && m.geometry && !shared.has(m.geometry)) m.geometry.dispose();
    if (!('material' in m) || !m.material) return;
    const mats = new Set(Array.isArray(m.material) ? m.material : [m.material]);
    for (const mat of mats) {
      if (shared.has(mat)) continue;
      const map = (mat as THREE.MeshStandardMaterial).map;
      if (map) map.dispose();
      mat.dispose();
    }
  });
}

/** Relative luminance of a CSS colour (0 black, 1 white), to pick a readable label colour. */
function luminance(hex: string): number {
  const c = new THREE.Color(hex);
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

/** The room around the workcell: sky light, a shadow-casting sun, the floor and its grid. */
export function addRoom(scene: THREE.Scene): void {
  const hemi = new THREE.HemisphereLight(0xdfe8ff, 0x2a2420, 1.4);
  hemi.position.set(0, 0, 2);
  scene.add(hemi);
  const sun = new THREE.DirectionalLight(0xffffff, 2.2);
  sun.position.set(1.2, -1.0, 2.4);
  sun.castShadow = true;
  sun.shadow.mapSize.set(1024, 1024);
  const sc = sun.shadow.camera;
  sc.left = sc.bottom = -1.6;
  sc.right = sc.top = 1.6;
  sc.near = 0.5;
  sc.far = 6;
  sun.shadow.bias = -0.0005;
  scene.add(sun);

  const floor = new THREE.Mesh(
    new THREE.PlaneGeometry(20, 20),
    new THREE.MeshStandardMaterial({ color: 0x1b1f26, roughness: 0.95 }),
  );
  floor.name = 'floor';
  floor.receiveShadow = true;
  floor.position.z = -0.75;
  scene.add(floor);
  const grid = new THREE.GridHelper(8, 32, 0x2d333d, 0x232830);
  grid.rotation.x = Math.PI / 2;
  grid.position.z = -0.749;
  scene.add(grid);
}

/** A body's meshes (a labelled block, a table, the shelf, the hook's parts) and its half height. */
export function bodyObject(b: BodySnapshot): { object: THREE.Group; halfZ: number } {
  const group = new THREE.Group();
  group.name = b.name;
  group.userData = { body: b.name, kind: b.kind };
  const parts =
    b.shape.type === 'cuboid'
      ? [{ pose: { position: [0, 0, 0], quaternion: [0, 0, 0, 1] } as PoseSnapshot, half_extents: b.shape.half_extents }]
      : b.shape.parts;
  let halfZ = 0;
  for (const p of parts) {
    const [hx, hy, hz] = p.half_extents;
    halfZ = Math.max(halfZ, hz + Math.abs(p.pose.position[2]));
    const geo = new THREE.BoxGeometry(2 * hx, 2 * hy, 2 * hz);
    let mat: THREE.Material | THREE.Material[];
    if (b.kind === 'block') {
      const side = new THREE.MeshStandardMaterial({ map: labelTexture(b.name, b.color), roughness: 0.55 });
      mat = [side, side, side, side, side, side];
    } else if (b.kind === 'table') {
      mat = new THREE.MeshStandardMaterial({ color: b.color, roughness: 0.85, metalness: 0.0 });
    } else if (b.kind === 'shelf') {
      mat = new THREE.MeshStandardMaterial({ color: b.color, roughness: 0.7 });
    } else {
      mat = new THREE.MeshStandardMaterial({ color: b.color, roughness: 0.35, metalness: 0.4 });
    }
    const m = new THREE.Mesh(geo, mat);
    applyPose(m, p.pose);
    m.castShadow = b.kind !== 'table';
    m.receiveShadow = true;
    m.userData = { body: b.name, kind: b.kind, lostAware: b.kind === 'block' || b.kind === 'hook' };
    group.add(m);
    if (b.kind === 'block' || b.kind === 'hook') {
      const edges = new THREE.LineSegments(
        new THREE.EdgesGeometry(geo),
        new THREE.LineBasicMaterial({ color: 0x000000, transparent: true, opacity: 0.35 }),
      );
      applyPose(edges, p.pose);
      group.add(edges);
    }
  }
  return { object: group, halfZ };
}

/** A region's patch on the table and its name label. */
export function regionObjects(r: WorldSnapshot['regions'][number]): [THREE.Mesh, THREE.Sprite] {
  const w = r.max[0] - r.min[0];
  const h = r.max[1] - r.min[1];
  const m = new THREE.Mesh(
    new THREE.PlaneGeometry(w, h),
    new THREE.MeshBasicMaterial({ color: r.color, transparent: true, opacity: 0.22, depthWrite: false }),
  );
  m.position.set((r.min[0] + r.max[0]) / 2, (r.min[1] + r.max[1]) / 2, 0.0015);
  m.name = `region:${r.name}`;
  const label = new THREE.Sprite(
    new THREE.SpriteMaterial({ map: textTexture(r.name), transparent: true, depthWrite: false }),
  );
  label.position.set((r.min[0] + r.max[0]) / 2, r.min[1] + 0.03, 0.01);
  label.scale.set(0.24, 0.06, 1);
  return [m, label];
}
