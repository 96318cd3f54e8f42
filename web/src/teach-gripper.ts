/**
 * The draggable 3-D gripper handle of Teach mode: a ball (drag: move in the horizontal plane), a
 * blue arrow (drag: up/down), a green ring (drag: turn the gripper about the vertical) and two
 * finger marks showing the yaw and whether the gripper is open. The handle shows the commanded
 * pose; the arm follows it by IK in the worker. It takes the pointer before the view's block drag
 * and orbit controls only when the pointer is on the handle.
 */
import * as THREE from 'three';
import type { View } from './view';

export interface HandlePose {
  position: [number, number, number];
  yaw: number;
}

type Part = 'move' | 'lift' | 'turn';

const UP = new THREE.Vector3(0, 0, 1);
/** Lowest and highest commanded TCP height (m): the fingertips stay above the floor of the table. */
const Z_MIN = 0.005;
const Z_MAX = 0.8;

export class GripperHandle {
  readonly group = new THREE.Group();
  private readonly ball: THREE.Mesh;
  private readonly arrow: THREE.Group;
  private readonly ring: THREE.Mesh;
  private readonly fingers: THREE.Mesh[] = [];
  private readonly raycaster = new THREE.Raycaster();
  private pose: HandlePose = { position: [0.3, 0, 0.3], yaw: 0 };
  private closed = false;
  private drag: { part: Part; offset: THREE.Vector3; startAngle: number; startYaw: number; pointerId: number } | null = null;
  enabled = false;

  constructor(
    private readonly view: View,
    host: HTMLElement,
    private readonly onMove: (p: HandlePose, final: boolean) => void,
  ) {
    const mat = (color: number, opacity = 0.85) =>
      new THREE.MeshBasicMaterial({ color, transparent: true, opacity, depthTest: false, depthWrite: false });
    this.ball = new THREE.Mesh(new THREE.SphereGeometry(0.022, 20, 14), mat(0xffb224));
    this.ball.userData.part = 'move';
    const shaft = new THREE.Mesh(new THREE.CylinderGeometry(0.006, 0.006, 0.08, 10), mat(0x3e63dd));
    shaft.rotation.x = Math.PI / 2;
    shaft.position.z = 0.06;
    const tip = new THREE.Mesh(new THREE.ConeGeometry(0.016, 0.035, 14), mat(0x3e63dd));
    tip.rotation.x = Math.PI / 2;
    tip.position.z = 0.115;
    shaft.userData.part = tip.userData.part = 'lift';
    this.arrow = new THREE.Group();
    this.arrow.add(shaft, tip);
    this.ring = new THREE.Mesh(new THREE.TorusGeometry(0.07, 0.006, 8, 48), mat(0x46a758, 0.8));
    this.ring.userData.part = 'turn';
    for (const side of [-1, 1]) {
      const f = new THREE.Mesh(new THREE.BoxGeometry(0.012, 0.01, 0.03), mat(0xe6edf3, 0.9));
      f.userData.side = side;
      this.fingers.push(f);
    }
    this.group.add(this.ball, this.arrow, this.ring, ...this.fingers);
    this.group.renderOrder = 10;
    this.group.traverse((o) => (o.renderOrder = 10));
    this.group.visible = false;
    view.scene.add(this.group);

    // Capture phase on the host: the handle sees the pointer before the canvas (block drag, orbit).
    host.addEventListener('pointerdown', (e) => this.onDown(e), true);
    host.addEventListener('pointermove', (e) => this.onMoveEvent(e), true);
    host.addEventListener('pointerup', (e) => this.onUp(e), true);
    host.addEventListener('pointercancel', () => (this.drag = null), true);
  }

  /** Shows the handle at `p` (the arm's gripper) unless the user is dragging it. */
  set(p: HandlePose, closed: boolean): void {
    if (!this.drag) this.pose = { position: [...p.position], yaw: p.yaw };
    this.closed = closed;
    this.draw();
  }

  show(on: boolean): void {
    this.enabled = on;
    this.group.visible = on;
    if (!on) this.drag = null;
    this.redraw();
  }

  get current(): HandlePose {
    return { position: [...this.pose.position], yaw: this.pose.yaw };
  }

  /** Whether a drag of the handle is under way. */
  get dragging(): boolean {
    return this.drag !== null;
  }

  /** Client coordinates of a part (for tests and hints). */
  screenPosition(part: Part): { x: number; y: number } {
    const obj = part === 'move' ? this.ball : part === 'lift' ? this.arrow.children[1] : this.ring;
    const v = new THREE.Vector3();
    if (part === 'turn') {
      // A point on the ring on the side facing the camera's right.
      const right = new THREE.Vector3().setFromMatrixColumn(this.view.camera.matrixWorld, 0);
      right.z = 0;
      right.normalize().multiplyScalar(0.07);
      v.copy(this.group.position).add(right);
    } else obj.getWorldPosition(v);
    return this.view.project([v.x, v.y, v.z]);
  }

  private draw(): void {
    const [x, y, z] = this.pose.position;
    this.group.position.set(x, y, z);
    const c = Math.cos(this.pose.yaw);
    const s = Math.sin(this.pose.yaw);
    // Fingers close across the yaw direction rotated by 90° (sim::panda::down_orientation).
    const gap = this.closed ? 0.014 : 0.045;
    for (const f of this.fingers) {
      const side = f.userData.side as number;
      f.position.set(-s * side * gap, c * side * gap, -0.012);
      f.rotation.set(0, 0, this.pose.yaw);
    }
    this.redraw();
  }

  private redraw(): void {
    this.view.controls.dispatchEvent({ type: 'change' });
  }

  private setRay(e: PointerEvent): void {
    const r = this.view.renderer.domElement.getBoundingClientRect();
    const p = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(p, this.view.camera);
  }

  private horizontalHit(z: number): THREE.Vector3 | null {
    const p = new THREE.Vector3();
    return this.raycaster.ray.intersectPlane(new THREE.Plane(UP, -z), p) ? p : null;
  }

  /** The point of the ray on the vertical plane through the handle facing the camera. */
  private verticalHit(): THREE.Vector3 | null {
    const n = new THREE.Vector3().subVectors(this.view.camera.position, this.group.position);
    n.z = 0;
    if (n.lengthSq() < 1e-9) return null;
    n.normalize();
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(n, this.group.position);
    const p = new THREE.Vector3();
    return this.raycaster.ray.intersectPlane(plane, p) ? p : null;
  }

  private onDown(e: PointerEvent): void {
    if (!this.enabled || e.button !== 0) return;
    this.setRay(e);
    const hit = this.raycaster.intersectObject(this.group, true).find((h) => h.object.userData.part);
    if (!hit) return;
    e.stopPropagation();
    e.preventDefault();
    const part = hit.object.userData.part as Part;
    const centre = this.group.position.clone();
    let offset = new THREE.Vector3();
    let startAngle = 0;
    if (part === 'move') {
      const h = this.horizontalHit(centre.z);
      if (h) offset = h.sub(centre);
    } else if (part === 'lift') {
      const h = this.verticalHit();
      if (h) offset = h.sub(centre);
    } else {
      const h = this.horizontalHit(centre.z);
      if (h) startAngle = Math.atan2(h.y - centre.y, h.x - centre.x);
    }
    this.drag = { part, offset, startAngle, startYaw: this.pose.yaw, pointerId: e.pointerId };
    try {
      this.view.renderer.domElement.setPointerCapture(e.pointerId);
    } catch {
      /* synthetic pointers may not be capturable */
    }
    this.view.renderer.domElement.style.cursor = 'grabbing';
  }

  private onMoveEvent(e: PointerEvent): void {
    const d = this.drag;
    if (!d) {
      if (!this.enabled) return;
      this.setRay(e);
      const over = this.raycaster.intersectObject(this.group, true).some((h) => h.object.userData.part);
      if (over) this.view.renderer.domElement.style.cursor = 'grab';
      return;
    }
    e.stopPropagation();
    this.setRay(e);
    const [x, y, z] = this.pose.position;
    if (d.part === 'move') {
      const h = this.horizontalHit(z);
      if (h) this.pose.position = [h.x - d.offset.x, h.y - d.offset.y, z];
    } else if (d.part === 'lift') {
      const h = this.verticalHit();
      if (h) this.pose.position = [x, y, Math.min(Z_MAX, Math.max(Z_MIN, h.z - d.offset.z))];
    } else {
      const h = this.horizontalHit(z);
      if (h) {
        const a = Math.atan2(h.y - y, h.x - x);
        let yaw = d.startYaw + (a - d.startAngle);
        yaw = Math.atan2(Math.sin(yaw), Math.cos(yaw));
        this.pose.yaw = yaw;
      }
    }
    this.draw();
    this.onMove(this.current, false);
  }

  private onUp(e: PointerEvent): void {
    const d = this.drag;
    if (!d) return;
    e.stopPropagation();
    this.drag = null;
    try {
      this.view.renderer.domElement.releasePointerCapture(d.pointerId);
    } catch {
      /* already released */
    }
    this.view.renderer.domElement.style.cursor = '';
    this.onMove(this.current, true);
  }
}
