/**
 * The reach shading shown while the user drags a block: each arm's workspace annulus (the scene
 * graph's `inreach`: between the snapshot's min and max radius around the arm's base) as a flat
 * translucent ring just above the table, and whether a point lies inside any of them (the drag
 * ghost turns red outside). The core has the last word on a drop (IK of the grasp); this is the
 * quick picture of where that can succeed.
 */
import * as THREE from 'three';
import type { WorldSnapshot } from 'logic-lfd';

/** Height of the rings above the surface under the dragged block (m), so they do not flicker. */
const LIFT = 0.003;
const RING_COLOR = 0x46a758;
const RING_OPACITY = 0.18;

export class ReachShading {
  readonly group = new THREE.Group();
  private rings: { x: number; y: number; lo: number; hi: number }[] = [];
  private readonly material = new THREE.MeshBasicMaterial({
    color: RING_COLOR,
    transparent: true,
    opacity: RING_OPACITY,
    depthWrite: false,
    side: THREE.DoubleSide,
  });

  constructor() {
    this.group.name = 'reach-shading';
    this.group.visible = false;
  }

  /** Shows the arms' rings of snapshot `s` at height `z` (m). */
  show(s: WorldSnapshot, z: number): void {
    this.clear();
    this.rings = s.arms.map((a) => ({ x: a.base.position[0], y: a.base.position[1], lo: a.reach.min_radius, hi: a.reach.max_radius }));
    for (const r of this.rings) {
      const m = new THREE.Mesh(new THREE.RingGeometry(r.lo, r.hi, 96, 1), this.material);
      m.position.set(r.x, r.y, z + LIFT);
      m.renderOrder = 1;
      this.group.add(m);
    }
    this.group.visible = true;
  }

  hide(): void {
    this.clear();
    this.group.visible = false;
  }

  /** Whether (x, y) lies within some arm's ring. */
  covers(x: number, y: number): boolean {
    return this.rings.some((r) => {
      const d = Math.hypot(x - r.x, y - r.y);
      return d >= r.lo && d <= r.hi;
    });
  }

  private clear(): void {
    for (const c of [...this.group.children]) {
      c.removeFromParent();
      (c as THREE.Mesh).geometry.dispose();
    }
    this.rings = [];
  }
}
