/**
 * The 3-D view: draws a WorldSnapshot (tables, shelf, regions, labelled blocks, hook, arms as
 * capsules or with the robot's meshes: view-arms.ts) with three.js, z up, an orbit camera, and
 * lets the user drag a block with the mouse (raycast onto the support under the pointer; the drop
 * is sent to the worker, which accepts or refuses it).
 */
import { SHIPPED_ROBOTS } from './robot-choice';
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { BodySnapshot, WorldSnapshot } from 'logic-lfd';
import type { ReachShading } from './reach-shading';
import { ArmDrawings, type ArmMeshInfo, type ArmStyle } from './view-arms';
import { addRoom, applyPose, bodyObject, disposeObject, isSoftwareRenderer, regionObjects } from './view-scene';

export interface DropRequest {
  body: string;
  position: [number, number, number];
}

export interface ViewOptions {
  /** Called when the user releases a dragged block; resolves to a refusal message or null. */
  onDrop: (d: DropRequest) => Promise<string | null>;
  /** Called when a drag starts (the page pauses the run meanwhile). */
  onDragStart?: (body: string) => void;
  /** Called when a drag has ended, after its drop was accepted or refused (or it was cancelled). */
  onDragEnd?: () => void;
  /** Shows a short message over the view (refused drops). */
  onNotice?: (text: string, kind: 'info' | 'error') => void;
  /** Why no block may be dragged now (null: it may). */
  dragRefusal?: () => string | null;
}

const UP = new THREE.Vector3(0, 0, 1);
/** How long a disturbance's move stays marked (ms). */
const MOVE_MARK_MS = 3000;

interface BodyEntry {
  object: THREE.Object3D;
  kind: BodySnapshot['kind'];
  shapeKey: string;
  halfZ: number;
}

export class View {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  private readonly bodies = new Map<string, BodyEntry>();
  private readonly regions = new THREE.Group();
  private readonly targets = new THREE.Group();
  private readonly trail: THREE.Line;
  private trailPoints: THREE.Vector3[] = [];
  /** Loaded after the first frame (`loadExtras`): a drag before that shows no shading. */
  private reach: ReachShading | null = null;
  /** The arms: capsules, and the Panda's meshes once `loadExtras` has loaded them. */
  private readonly arms: ArmDrawings;
  private readonly raycaster = new THREE.Raycaster();
  private readonly pointer = new THREE.Vector2();
  private drag: { name: string; ghost: THREE.Mesh; target: THREE.Vector3 | null; halfZ: number; planeZ: number } | null =
    null;
  private snapshot: WorldSnapshot | null = null;
  private sceneName = '';
  private hovered: string | null = null;
  private rendering = false;
  /** Smoothed time of one `renderer.render` call (ms). */
  renderMs = 0;
  /** Whether the renderer runs in software (SwiftShader) or `?quality=low` was asked for. */
  readonly lowQuality: boolean;
  private dirty = true;
  /** Told where a dragged block would land (null: the drag ended); set by Teach mode. */
  dragHint: ((body: string, p: THREE.Vector3 | null) => void) | null = null;

  constructor(
    private readonly host: HTMLElement,
    private readonly opts: ViewOptions,
  ) {
    // A software rasteriser (SwiftShader: headless browsers, machines without a GPU) gets the light
    // settings: no MSAA, no shadows, fewer pixels; it stays interactive instead of 2 frames/s.
    const q = new URLSearchParams(location.search).get('quality');
    this.lowQuality = q === 'low' || (q !== 'high' && isSoftwareRenderer());
    this.renderer = new THREE.WebGLRenderer({ antialias: !this.lowQuality });
    this.renderer.setPixelRatio(this.lowQuality ? 0.75 : Math.min(window.devicePixelRatio, 2));
    this.renderer.shadowMap.enabled = !this.lowQuality;
    this.renderer.shadowMap.type = THREE.PCFShadowMap;
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    this.renderer.domElement.setAttribute('aria-label', '3-D view of the robot workcell: drag a block to move it');
    this.renderer.domElement.setAttribute('role', 'img');
    this.renderer.domElement.tabIndex = 0;
    host.appendChild(this.renderer.domElement);

    this.scene.background = new THREE.Color(0x14171c);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.02, 50);
    this.camera.up.copy(UP);
    this.camera.position.set(1.45, -1.25, 1.05);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0.45, 0, 0.1);
    this.controls.enableDamping = true;
    this.controls.maxPolarAngle = Math.PI * 0.49;
    this.controls.minDistance = 0.3;
    this.controls.maxDistance = 6;
    this.controls.addEventListener('change', () => (this.dirty = true));

    // `?arm=capsules` starts with the capsules.
    const style: ArmStyle = new URLSearchParams(location.search).get('arm') === 'capsules' ? 'capsules' : 'meshes';
    this.arms = new ArmDrawings(this.scene, this.shared, (o) => this.dropObject(o), !this.lowQuality, style);
    addRoom(this.scene);
    this.scene.add(this.regions, this.targets);
    this.trail = new THREE.Line(
      new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ color: 0xffb224, transparent: true, opacity: 0.85 }),
    );
    this.trail.frustumCulled = false;
    this.scene.add(this.trail);

    const el = this.renderer.domElement;
    el.addEventListener('pointerdown', (e) => this.onPointerDown(e));
    el.addEventListener('pointermove', (e) => this.onPointerMove(e));
    el.addEventListener('pointerup', (e) => void this.onPointerUp(e));
    el.addEventListener('pointercancel', () => this.cancelDrag());
    new ResizeObserver(() => this.resize()).observe(host);
    this.resize();
  }

  /** Loads what the first frame does without: the reach shading a drag shows, and the robot's
   * meshes (with the Capsules / Meshes switch), each in a chunk of its own. */
  loadExtras(): void {
    void import('./reach-shading').then(({ ReachShading }) => {
      this.reach = new ReachShading();
      this.scene.add(this.reach.group);
      this.renderer.domElement.dataset.extras = 'loaded';
    });
    const canvas = this.renderer.domElement;
    canvas.dataset.armStyle = this.arms.style;
    void import('./robot-meshes').then(({ RobotModel, armStyleSwitch }) => {
      // Each robot's meshes are fetched once, when an arm first shows it (the Panda at once).
      const asked = new Set<string>();
      const loaded: string[] = [];
      const load = async (name: string) => {
        if (asked.has(name)) return;
        asked.add(name);
        if (!SHIPPED_ROBOTS.some(([n]) => n === name)) {
          this.opts.onNotice?.(`The robot ${name} is drawn as capsules fitted to its collision shapes: the page has meshes for its own robots only.`, 'info');
          return;
        }
        let robot;
        try {
          robot = await RobotModel.load(new URL(`robots/${name}/`, document.baseURI));
        } catch (e) {
          canvas.dataset.meshes = loaded.length ? 'loaded' : 'failed';
          this.opts.onNotice?.(`The robot's meshes could not be loaded (${(e as Error).message}): the arms stay drawn as capsules.`, 'error');
          return;
        }
        this.arms.setRobot(name, robot, this.snapshot?.arms ?? []);
        if (!loaded.length) armStyleSwitch(this.host, this.arms.style, (s) => this.setArmStyle(s));
        loaded.push(name);
        this.dirty = true;
        canvas.dataset.meshes = 'loaded';
        canvas.dataset.meshesOf = loaded.join(' ');
      };
      this.arms.want = (name) => void load(name);
      void load('panda');
      for (const a of this.snapshot?.arms ?? []) void load(a.robot ?? 'panda');
    });
  }

  /** Draws the arms as capsules or with the robot's meshes (capsules while the meshes load). */
  setArmStyle(style: ArmStyle): void {
    this.arms.setStyle(style);
    this.renderer.domElement.dataset.armStyle = style;
    this.dirty = true;
  }

  /** Starts the render loop (renders only when something changed). */
  start(): void {
    if (this.rendering) return;
    this.rendering = true;
    const loop = () => {
      this.controls.update();
      if (this.dirty) {
        const t0 = performance.now();
        this.renderer.render(this.scene, this.camera);
        this.renderMs = 0.9 * this.renderMs + 0.1 * (performance.now() - t0);
        this.dirty = false;
      }
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  private resize(): void {
    const w = Math.max(1, this.host.clientWidth);
    const h = Math.max(1, this.host.clientHeight);
    this.renderer.setSize(w, h, false);
    this.renderer.domElement.style.width = `${w}px`;
    this.renderer.domElement.style.height = `${h}px`;
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  /** Frames the camera on the scene's bodies (called when a new scene is loaded). */
  private frameCamera(s: WorldSnapshot): void {
    const box = new THREE.Box3();
    for (const b of s.bodies) {
      const c = new THREE.Vector3(...b.pose.position);
      const h = b.shape.type === 'cuboid' ? new THREE.Vector3(...b.shape.half_extents) : new THREE.Vector3();
      box.expandByPoint(c.clone().sub(h)).expandByPoint(c.clone().add(h));
    }
    for (const a of s.arms) {
      box.expandByPoint(new THREE.Vector3(...a.base.position));
      for (const l of a.links) box.expandByPoint(new THREE.Vector3(...l.b));
    }
    if (box.isEmpty()) return;
    const c = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3()).length();
    // A portrait view (a phone) needs more distance to show the same width.
    const d = Math.max(1.2, size * 1.2) * Math.max(1, 1 / this.camera.aspect);
    this.controls.target.set(c.x, c.y, Math.max(0.05, c.z * 0.6));
    this.camera.position.set(c.x + d * 0.55, c.y - d * 0.8, c.z + d * 0.55);
    this.controls.update();
  }

  /** Draws a snapshot (creating meshes the first time a body appears); `trail: false` leaves the
   * end-effector trail as it is (a past moment shown from the timeline). */
  update(s: WorldSnapshot, ee?: { arm: number; pos: number[]; target: number[] }[], trail = true): void {
    const fresh = s.name !== this.sceneName;
    if (fresh) {
      this.clearScene();
      this.sceneName = s.name;
    }
    this.snapshot = s;
    const seen = new Set<string>();
    for (const b of s.bodies) {
      seen.add(b.name);
      let e = this.bodies.get(b.name);
      const key = JSON.stringify(b.shape) + b.color;
      if (!e || e.shapeKey !== key) {
        if (e) this.dropObject(e.object);
        e = { ...bodyObject(b), kind: b.kind, shapeKey: key };
        this.bodies.set(b.name, e);
        this.scene.add(e.object);
      }
      if (this.drag?.name !== b.name) applyPose(e.object, b.pose);
      e.object.visible = true;
      const lost = !!b.lost;
      e.object.traverse((o) => {
        if (o instanceof THREE.Mesh && o.userData.lostAware) {
          const m = o.material as THREE.MeshStandardMaterial | THREE.MeshStandardMaterial[];
          for (const mm of Array.isArray(m) ? m : [m]) {
            mm.transparent = lost;
            mm.opacity = lost ? 0.45 : 1;
          }
        }
      });
    }
    for (const [name, e] of this.bodies) {
      if (!seen.has(name)) {
        this.dropObject(e.object);
        this.bodies.delete(name);
      }
    }
    if (fresh) this.drawRegions(s);
    s.arms.forEach((a, i) => this.arms.update(i, a));
    this.arms.trim(s.arms.length);
    this.updateTargets(ee ?? [], trail);
    if (fresh) this.frameCamera(s);
    this.dirty = true;
  }

  /** Removes an object from the scene and frees what only it uses. */
  private dropObject(o: THREE.Object3D): void {
    o.removeFromParent();
    // The mark's ghost may borrow this object's geometry: drawn once more after the dispose,
    // the geometry would be uploaded again and never freed.
    const ghost = this.moveMark.ghost;
    let borrowed = false;
    o.traverse((c) => {
      if (c instanceof THREE.Mesh && c.geometry === ghost.geometry) borrowed = true;
    });
    if (borrowed) {
      this.moveMark.group.visible = false;
      ghost.geometry = this.targetGeometry;
    }
    disposeObject(o, this.shared);
  }

  private clearScene(): void {
    // The mark's ghost borrows a block's geometry, which is freed with the block: drawn after
    // that, the geometry would be uploaded again and never freed.
    this.moveMark.group.visible = false;
    for (const e of this.bodies.values()) this.dropObject(e.object);
    this.bodies.clear();
    this.arms.trim();
    this.clearRegions();
    this.clearTrail();
    this.cancelDrag();
  }

  /** Clears the end-effector trail (on reset). */
  clearTrail(): void {
    this.trailPoints = [];
    this.trail.geometry.dispose();
    this.trail.geometry = new THREE.BufferGeometry();
    this.dirty = true;
  }

  private clearRegions(): void {
    for (const c of [...this.regions.children]) this.dropObject(c);
  }

  private drawRegions(s: WorldSnapshot): void {
    this.clearRegions();
    for (const r of s.regions) this.regions.add(...regionObjects(r));
  }

  private readonly targetGeometry = new THREE.SphereGeometry(0.012, 12, 8);
  private readonly targetMaterial = new THREE.MeshBasicMaterial({ color: 0xffb224, transparent: true, opacity: 0.9 });
  /** Geometries and materials shared by many meshes: never disposed with one of them. */
  private readonly shared = new Set<unknown>([
    this.targetGeometry,
    this.targetMaterial,
  ]);

  private updateTargets(ee: { arm: number; pos: number[]; target: number[] }[], trail: boolean): void {
    while (this.targets.children.length < ee.length) this.targets.add(new THREE.Mesh(this.targetGeometry, this.targetMaterial));
    this.targets.children.forEach((m, i) => {
      const p = ee[i];
      m.visible = !!p;
      if (!p) return;
      m.position.set(p.target[0], p.target[1], p.target[2]);
      if (p.arm === 0 && trail) {
        const v = new THREE.Vector3(p.pos[0], p.pos[1], p.pos[2]);
        const last = this.trailPoints[this.trailPoints.length - 1];
        if (!last || last.distanceTo(v) > 0.004) {
          this.trailPoints.push(v);
          if (this.trailPoints.length > 600) this.trailPoints.shift();
          this.trail.geometry.dispose();
          this.trail.geometry = new THREE.BufferGeometry().setFromPoints(this.trailPoints);
        }
      }
    });
  }

  // ---- dragging ----

  private setPointer(e: PointerEvent): void {
    const r = this.renderer.domElement.getBoundingClientRect();
    this.pointer.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(this.pointer, this.camera);
  }

  private pickBlock(): string | null {
    const blocks = [...this.bodies.values()].filter((b) => b.kind === 'block').map((b) => b.object);
    // Only the block meshes count (edge lines would match any ray passing nearby).
    const hit = this.raycaster.intersectObjects(blocks, true).find((h) => h.object instanceof THREE.Mesh);
    return hit ? (hit.object.userData.body as string) : null;
  }

  private onPointerDown(e: PointerEvent): void {
    if (e.button !== 0) return;
    this.setPointer(e);
    const name = this.pickBlock();
    if (!name) return;
    const refusal = this.opts.dragRefusal?.();
    if (refusal) {
      this.opts.onNotice?.(refusal, 'info');
      return;
    }
    const entry = this.bodies.get(name)!;
    this.controls.enabled = false;
    this.renderer.domElement.setPointerCapture(e.pointerId);
    const src = entry.object.children.find((c): c is THREE.Mesh => c instanceof THREE.Mesh)!;
    const ghost = new THREE.Mesh(
      src.geometry,
      new THREE.MeshStandardMaterial({ color: 0xffffff, transparent: true, opacity: 0.35, depthWrite: false }),
    );
    ghost.visible = false;
    this.scene.add(ghost);
    this.drag = { name, ghost, target: null, halfZ: entry.halfZ, planeZ: entry.object.position.z };
    if (this.snapshot) this.reach?.show(this.snapshot, tableTop(this.snapshot));
    this.renderer.domElement.dataset.reachShown = String(!!this.reach);
    this.opts.onDragStart?.(name);
    this.onPointerMove(e);
  }

  private onPointerMove(e: PointerEvent): void {
    this.setPointer(e);
    if (!this.drag) {
      const h = this.pickBlock();
      if (h !== this.hovered) {
        this.hovered = h;
        this.renderer.domElement.style.cursor = h ? 'grab' : '';
      }
      return;
    }
    this.renderer.domElement.style.cursor = 'grabbing';
    const d = this.drag;
    // Surfaces a block may be dropped on: tops of tables, the shelf and the other blocks.
    const supports = [...this.bodies.entries()]
      .filter(([n, b]) => n !== d.name && (b.kind === 'table' || b.kind === 'shelf' || b.kind === 'block'))
      .map(([, b]) => b.object);
    const hits = this.raycaster.intersectObjects(supports, true).filter((h) => h.object instanceof THREE.Mesh);
    let target: THREE.Vector3 | null = null;
    for (const h of hits) {
      if (!h.face) continue;
      const n = h.face.normal.clone().transformDirection(h.object.matrixWorld);
      if (n.dot(UP) > 0.7) {
        target = h.point.clone().add(new THREE.Vector3(0, 0, d.halfZ + 0.002));
        break;
      }
    }
    if (!target) {
      const plane = new THREE.Plane(UP, -d.planeZ);
      const p = new THREE.Vector3();
      if (this.raycaster.ray.intersectPlane(plane, p)) target = p;
    }
    d.target = target;
    this.dragHint?.(d.name, target);
    d.ghost.visible = !!target;
    if (target) {
      d.ghost.position.copy(target);
      // Red outside every arm's ring (a hook may still pull a block in from beyond).
      const reachable = (this.reach?.covers(target.x, target.y) ?? true) || !!this.snapshot?.bodies.some((b) => b.kind === 'hook');
      (d.ghost.material as THREE.MeshStandardMaterial).color.set(reachable ? 0xffffff : 0xe5484d);
      this.renderer.domElement.dataset.dropReachable = String(reachable);
    }
    const obj = this.bodies.get(d.name)?.object;
    if (obj && target) obj.position.set(target.x, target.y, target.z + 0.04);
    this.dirty = true;
  }

  private async onPointerUp(e: PointerEvent): Promise<void> {
    const d = this.drag;
    if (!d) return;
    this.renderer.domElement.releasePointerCapture(e.pointerId);
    this.drag = null;
    this.dragHint?.(d.name, null);
    this.reach?.hide();
    this.renderer.domElement.dataset.reachShown = 'false';
    this.dropGhost(d.ghost);
    this.controls.enabled = true;
    this.renderer.domElement.style.cursor = '';
    try {
      if (d.target) {
        const refusal = await this.opts.onDrop({ body: d.name, position: [d.target.x, d.target.y, d.target.z] });
        if (refusal) this.opts.onNotice?.(`Drop refused: ${refusal}`, 'error');
      }
    } finally {
      if (this.snapshot) this.update(this.snapshot);
      this.opts.onDragEnd?.();
    }
  }

  /** The drag ghost borrows the block's geometry: only its own material is freed. */
  private dropGhost(g: THREE.Mesh): void {
    g.removeFromParent();
    (g.material as THREE.Material).dispose();
  }

  private cancelDrag(): void {
    if (!this.drag) return;
    this.dragHint?.(this.drag.name, null);
    this.dropGhost(this.drag.ghost);
    this.reach?.hide();
    this.renderer.domElement.dataset.reachShown = 'false';
    this.drag = null;
    this.controls.enabled = true;
    if (this.snapshot) this.update(this.snapshot);
    this.opts.onDragEnd?.();
  }

  /** Marks a disturbance's move of `body` for a few seconds: a yellow ghost where it was and a
   * line to where it is. One mark at a time, its objects reused (nothing to leak). */
  markMove(body: string, from: [number, number, number]): void {
    const e = this.bodies.get(body);
    const src = e?.object.children.find((c): c is THREE.Mesh => c instanceof THREE.Mesh);
    if (!e || !src) return;
    this.showMark(`moved:${body}`, src.geometry, e.object.quaternion, from, [e.object.position.x, e.object.position.y, e.object.position.z]);
  }

  /** Marks a push of an arm's hand (L1 while it moves, nothing else displaced) the same way: a
   * ghost ball where the hand was and a line to where the push left it. */
  markPush(arm: string, from: [number, number, number], to: [number, number, number]): void {
    // The targets' sphere, scaled to a 2 cm ball: a geometry of its own would be uploaded the first
    // time a hand is pushed, which the page soak's memory check would read as a leak.
    this.showMark(`pushed:${arm}`, this.targetGeometry, new THREE.Quaternion(), from, to, 0.02 / 0.012);
  }

  private showMark(name: string, geometry: THREE.BufferGeometry, rotation: THREE.Quaternion, from: [number, number, number], to: [number, number, number], scale = 1): void {
    const m = this.moveMark;
    m.ghost.geometry = geometry;
    m.ghost.scale.setScalar(scale);
    m.ghost.position.set(...from);
    m.ghost.quaternion.copy(rotation);
    const pos = m.line.geometry.getAttribute('position') as THREE.BufferAttribute;
    pos.setXYZ(0, ...from);
    pos.setXYZ(1, ...to);
    pos.needsUpdate = true;
    m.group.name = name;
    m.group.visible = true;
    this.dirty = true;
    clearTimeout(m.timer);
    m.timer = window.setTimeout(() => {
      m.group.visible = false;
      this.dirty = true;
    }, MOVE_MARK_MS);
  }

  private readonly moveMark = (() => {
    // Drawn over everything: the place a hand was pushed from is inside the hand itself.
    const ghost = new THREE.Mesh(undefined, new THREE.MeshBasicMaterial({ color: 0xffb224, transparent: true, opacity: 0.45, depthWrite: false, depthTest: false }));
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6), 3));
    const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xffb224, depthTest: false }));
    line.frustumCulled = false;
    ghost.renderOrder = line.renderOrder = 10;
    const group = new THREE.Group().add(ghost, line);
    group.visible = false;
    this.scene.add(group);
    return { group, ghost, line, timer: 0 };
  })();

  /** The disturbance marked now: `moved:<body>` or `pushed:<arm>` (at most one). */
  moveMarks(): string[] {
    return this.moveMark.group.visible ? [this.moveMark.group.name] : [];
  }

  /** Where each arm's meshes are drawn now (null entries: an arm without meshes yet). */
  armMeshes(): { style: ArmStyle; loaded: boolean; arms: (ArmMeshInfo | null)[] } {
    return { style: this.arms.style, loaded: this.arms.meshesLoaded, arms: this.arms.info() };
  }

  /** Where `body` is drawn now (world coordinates), or null if it is not in the scene. */
  bodyPosition(body: string): [number, number, number] | null {
    const p = this.bodies.get(body)?.object.position;
    return p ? [p.x, p.y, p.z] : null;
  }

  /** Projects a body's centre to client coordinates (for tests and tooltips). */
  screenPosition(body: string): { x: number; y: number } | null {
    const e = this.bodies.get(body);
    if (!e) return null;
    return this.toClient(e.object.getWorldPosition(new THREE.Vector3()));
  }

  /** Projects a world point to client coordinates. */
  project(p: [number, number, number]): { x: number; y: number } {
    return this.toClient(new THREE.Vector3(...p));
  }

  private toClient(world: THREE.Vector3): { x: number; y: number } {
    const v = world.project(this.camera);
    const r = this.renderer.domElement.getBoundingClientRect();
    return { x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height };
  }
}

/** The height of the highest table top in `s` (m; 0 without tables). */
function tableTop(s: WorldSnapshot): number {
  const tops = s.bodies.filter((b) => b.kind === 'table' && b.shape.type === 'cuboid').map((b) => b.pose.position[2] + (b.shape.type === 'cuboid' ? b.shape.half_extents[2] : 0));
  return tops.length ? Math.max(...tops) : 0;
}
