/**
 * Where a Quick-mode drop lands, and the marks that show it while the block is dragged: the block
 * that would receive it (`blockUnder`, the very rule the recorder's drop uses to choose stack over
 * place) is outlined, and a dark footprint lies where the dragged block would rest — on that
 * block's top, else on the surface under the pointer. From a fixed camera three blocks in a row
 * can look like a tower; the footprint says which it is before the drop.
 */
import * as THREE from 'three';
import type { BodySnapshot, WorldSnapshot } from 'logic-lfd';

/** How far (m) beside or below a block's top face a drop still stacks onto it. */
const DROP_MARGIN = 0.005;
/** The footprint floats this far (m) above its surface (no z-fighting). */
const LIFT = 0.0015;

type Cuboid = BodySnapshot & { shape: { type: 'cuboid'; half_extents: [number, number, number] } };

const isCuboid = (b: BodySnapshot): b is Cuboid => b.shape.type === 'cuboid';

/** A body's yaw about world z. */
function yawOf(b: BodySnapshot): number {
  const q = b.pose.quaternion;
  return Math.atan2(2 * (q[3] * q[2] + q[0] * q[1]), 1 - 2 * (q[1] * q[1] + q[2] * q[2]));
}

/** The block under a drop point (stack onto it), if the point is above one's top face. */
export function blockUnder(w: WorldSnapshot, body: string, p: readonly [number, number, number]): string | null {
  let best: { name: string; top: number } | null = null;
  for (const b of w.bodies) {
    if (b.kind !== 'block' || b.name === body || !isCuboid(b)) continue;
    const [hx, hy, hz] = b.shape.half_extents;
    const [x, y, z] = b.pose.position;
    const yaw = yawOf(b);
    const dx = p[0] - x;
    const dy = p[1] - y;
    const lx = Math.cos(yaw) * dx + Math.sin(yaw) * dy;
    const ly = -Math.sin(yaw) * dx + Math.cos(yaw) * dy;
    const top = z + hz;
    if (Math.abs(lx) <= hx + DROP_MARGIN && Math.abs(ly) <= hy + DROP_MARGIN && p[2] > top - DROP_MARGIN && (!best || top > best.top)) best = { name: b.name, top };
  }
  return best?.name ?? null;
}

/** What the marks show now (read by the page's tests). */
export interface DropHintState {
  body: string;
  /** The block that would receive the drop (null: the drop places the block). */
  onto: string | null;
  /** Centre of the contact footprint (world, m). */
  shadow: [number, number, number];
}

/** The receiving block's outline and the contact footprint, drawn in the view's scene. */
export class DropHint {
  private readonly group = new THREE.Group();
  private readonly shadow: THREE.Mesh;
  private readonly outline: THREE.LineSegments;
  private readonly glow: THREE.Mesh;
  private state: DropHintState | null = null;

  constructor(
    scene: THREE.Scene,
    private readonly redraw: () => void,
  ) {
    this.shadow = new THREE.Mesh(
      new THREE.PlaneGeometry(1, 1),
      new THREE.MeshBasicMaterial({ color: 0x000000, transparent: true, opacity: 0.7, depthWrite: false }),
    );
    const box = new THREE.BoxGeometry(1, 1, 1);
    this.outline = new THREE.LineSegments(new THREE.EdgesGeometry(box), new THREE.LineBasicMaterial({ color: 0x3dd68c, depthTest: false, transparent: true }));
    this.glow = new THREE.Mesh(box, new THREE.MeshBasicMaterial({ color: 0x3dd68c, transparent: true, opacity: 0.45, depthWrite: false }));
    this.outline.renderOrder = 9;
    this.group.add(this.shadow, this.outline, this.glow);
    this.group.visible = false;
    scene.add(this.group);
  }

  /** What is shown (null: nothing). */
  current(): DropHintState | null {
    return this.state;
  }

  /** Shows where `body`, dragged to `p` (the view's drop point), would land in `w`; null hides. */
  show(w: WorldSnapshot | null, body: string, p: THREE.Vector3 | null): void {
    const moved = w?.bodies.find((b) => b.name === body);
    if (!w || !p || !moved || !isCuboid(moved)) return this.hide();
    const [hx, hy, hz] = moved.shape.half_extents;
    const ontoName = blockUnder(w, body, [p.x, p.y, p.z]);
    const onto = ontoName ? w.bodies.find((b) => b.name === ontoName) : undefined;
    let at: [number, number, number];
    let yaw = yawOf(moved);
    // A little wider than the block, so that its rim shows around the drag ghost.
    let [sx, sy] = [2 * hx * 1.2, 2 * hy * 1.2];
    if (onto && isCuboid(onto)) {
      // Stacked: the robot sets it centred on the receiving block, square with it.
      const [ox, oy, oz] = onto.pose.position;
      const [bx, by, bz] = onto.shape.half_extents;
      at = [ox, oy, oz + bz + LIFT];
      yaw = yawOf(onto);
      // On a block no wider than the top it rests on.
      [sx, sy] = [Math.min(sx, 2 * bx), Math.min(sy, 2 * by)];
      this.outline.position.set(ox, oy, oz);
      this.glow.position.set(ox, oy, oz);
      this.outline.scale.set(2 * bx + 0.006, 2 * by + 0.006, 2 * bz + 0.006);
      this.glow.scale.copy(this.outline.scale);
      this.outline.rotation.set(0, 0, yaw);
      this.glow.rotation.set(0, 0, yaw);
    } else at = [p.x, p.y, p.z - hz + LIFT - 0.002];
    this.outline.visible = this.glow.visible = !!onto;
    this.shadow.position.set(...at);
    this.shadow.rotation.set(0, 0, yaw);
    this.shadow.scale.set(sx, sy, 1);
    this.group.visible = true;
    this.state = { body, onto: onto ? onto.name : null, shadow: at };
    this.redraw();
  }

  hide(): void {
    if (!this.state) return;
    this.state = null;
    this.group.visible = false;
    this.redraw();
  }
}
