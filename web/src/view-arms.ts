/**
 * The arms of the 3-D view: each drawn as the simulator sees it (base disc, link capsules, finger
 * boxes from the snapshot) and, once its robot's meshes are loaded (robot-meshes.ts), with the
 * meshes posed from the snapshot's joint angles and gripper opening; one of the two is shown. Each
 * arm takes the meshes of the robot its snapshot names (the Panda when it names none); a robot
 * whose hand has no meshes keeps the finger boxes beside its meshes.
 */
import * as THREE from 'three';
import type { ArmSnapshot } from 'logic-lfd';
import type { MeshPlacement, RobotInstance, RobotModel } from './robot-meshes';
import { applyPose } from './view-scene';

/** How the arms are drawn: the simulator's capsules, or the robot's meshes once loaded. */
export type ArmStyle = 'meshes' | 'capsules';

/** Where the view draws one arm's robot meshes (world frame), for the browser tests. */
export interface ArmMeshInfo extends MeshPlacement {
  name: string;
  /** Whether the meshes are shown (else the capsules are). */
  shown: boolean;
  /** The arm as it was drawn (the meshes' pose follows its joints; capsules, TCP to compare). */
  drawn: ArmSnapshot;
}

interface ArmEntry {
  /** The snapshot drawn last. */
  drawn: ArmSnapshot;
  group: THREE.Group;
  /** The capsule drawing: base disc, link capsules, finger boxes. */
  capsules: THREE.Group;
  /** The mesh drawing (null until the meshes are loaded, or for an arm they do not fit). */
  model: RobotInstance | null;
  /** The robot whose meshes `model` draws. */
  modelOf: string;
  /** The finger boxes (shown with the meshes when the robot's hand has none). */
  fingerBoxes: THREE.Group;
  links: THREE.Mesh[];
  linkKeys: string[];
  fingers: THREE.Mesh[];
  base: THREE.Mesh;
}

const Y = new THREE.Vector3(0, 1, 0);

export class ArmDrawings {
  private readonly entries: ArmEntry[] = [];
  /** The loaded meshes, by robot name. */
  private readonly robots = new Map<string, RobotModel>();
  /** Asks for a robot's meshes (once per name); set by the view when the meshes' chunk loads. */
  want: ((robot: string) => void) | null = null;
  private readonly linkMaterial = new THREE.MeshStandardMaterial({ color: 0xe9ecef, roughness: 0.45, metalness: 0.1 });
  private readonly jointMaterial = new THREE.MeshStandardMaterial({ color: 0x3a3f47, roughness: 0.5 });
  private readonly fingerMaterial = new THREE.MeshStandardMaterial({ color: 0x2b2f36, roughness: 0.6 });

  /**
   * `shared` collects what many meshes use (never freed with one of them); `drop` removes and
   * frees an object; `shadows` says whether the meshes cast shadows.
   */
  constructor(
    private readonly scene: THREE.Scene,
    private readonly shared: Set<unknown>,
    private readonly drop: (o: THREE.Object3D) => void,
    private readonly shadows: boolean,
    public style: ArmStyle,
  ) {
    for (const m of [this.linkMaterial, this.jointMaterial, this.fingerMaterial]) shared.add(m);
  }

  /** Whether some robot's meshes are loaded. */
  get meshesLoaded(): boolean {
    return this.robots.size > 0;
  }

  /** Draws the arms of robot `name` with `robot`'s meshes from now on (redrawing `arms` at once). */
  setRobot(name: string, robot: RobotModel, arms: readonly ArmSnapshot[]): void {
    this.robots.set(name, robot);
    for (const x of robot.shared) this.shared.add(x);
    arms.forEach((a, i) => this.update(i, a));
  }

  /** Shows the capsules or the meshes (capsules while the meshes load). */
  setStyle(style: ArmStyle): void {
    this.style = style;
    for (const e of this.entries) this.showStyle(e);
  }

  private showStyle(e: ArmEntry): void {
    const meshes = this.style === 'meshes' && !!e.model;
    e.capsules.visible = !meshes;
    e.fingerBoxes.visible = !meshes || !e.model?.prismatic.length;
    if (e.model) e.model.root.visible = meshes;
  }

  /** Draws arm `i` as in `a` (made the first time it appears). */
  update(i: number, a: ArmSnapshot): void {
    let e = this.entries[i];
    if (!e) {
      const group = new THREE.Group();
      group.name = `arm:${a.name}`;
      const capsules = new THREE.Group();
      const fingerBoxes = new THREE.Group();
      group.add(capsules, fingerBoxes);
      const base = new THREE.Mesh(new THREE.CylinderGeometry(0.09, 0.11, 0.04, 32), this.jointMaterial);
      base.rotation.x = Math.PI / 2;
      base.castShadow = true;
      capsules.add(base);
      e = { drawn: a, group, capsules, model: null, modelOf: '', fingerBoxes, links: [], linkKeys: [], fingers: [], base };
      this.entries[i] = e;
      this.scene.add(group);
    }
    e.drawn = a;
    e.base.position.set(a.base.position[0], a.base.position[1], a.base.position[2] + 0.02);
    a.links.forEach((c, j) => {
      const A = new THREE.Vector3(...c.a);
      const B = new THREE.Vector3(...c.b);
      const len = A.distanceTo(B);
      const key = `${c.radius.toFixed(4)}:${len.toFixed(4)}`;
      let m = e.links[j];
      if (!m || e.linkKeys[j] !== key) {
        if (m) this.drop(m);
        m = new THREE.Mesh(new THREE.CapsuleGeometry(c.radius, Math.max(len, 1e-4), 6, 16), this.linkMaterial);
        m.castShadow = true;
        m.receiveShadow = true;
        e.links[j] = m;
        e.linkKeys[j] = key;
        e.capsules.add(m);
      }
      m.position.copy(A).add(B).multiplyScalar(0.5);
      if (len > 1e-6) m.quaternion.setFromUnitVectors(Y, B.clone().sub(A).normalize());
    });
    a.fingers.forEach((f, j) => {
      let m = e.fingers[j];
      if (!m) {
        const [hx, hy, hz] = f.half_extents;
        m = new THREE.Mesh(new THREE.BoxGeometry(2 * hx, 2 * hy, 2 * hz), this.fingerMaterial);
        m.castShadow = true;
        e.fingers[j] = m;
        e.fingerBoxes.add(m);
      }
      applyPose(m, f.pose);
    });
    // The meshes of the arm's robot: its base pose is the URDF's base link, each finger slides
    // half the opening. The built-in Panda names no robot and has the Panda's chain.
    const name = a.robot ?? 'panda';
    if (e.model && e.modelOf !== name) {
      this.drop(e.model.root);
      e.model = null;
    }
    const robot = this.robots.get(name);
    if (!robot) this.want?.(name);
    if (robot && !e.model && a.joints.length === robot.dof) {
      e.model = robot.instantiate(this.shadows);
      e.modelOf = name;
      e.group.add(e.model.root);
    }
    if (e.model) {
      applyPose(e.model.root, a.base);
      e.model.pose(a.joints, a.gripper_opening / 2);
    }
    this.showStyle(e);
  }

  /** Removes the arms from `count` on (all by default). */
  trim(count = 0): void {
    while (this.entries.length > count) this.drop(this.entries.pop()!.group);
  }

  /** Where each arm's meshes are drawn now (null: an arm without meshes yet). */
  info(): (ArmMeshInfo | null)[] {
    return this.entries.map((e) => (e.model ? { name: e.drawn.name, shown: e.model.root.visible, drawn: e.drawn, ...e.model.placement() } : null));
  }
}
