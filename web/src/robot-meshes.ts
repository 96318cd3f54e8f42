/**
 * The arms drawn with the robot's own meshes (a chunk fetched after the first frame): the
 * kinematic tree of `robots/<robot>/robot.json` (written from the URDF by
 * scripts/robot-meshes/convert.mjs) with its compressed link meshes (.glb, meshopt), posed by forward
 * kinematics from a frame's joint angles and gripper opening; and the view's "Capsules / Meshes"
 * switch.
 */
import * as THREE from 'three';
import { MeshoptDecoder } from 'three/examples/jsm/libs/meshopt_decoder.module.js';
import { el } from './dom';
import { readGlb, type GlbMesh } from './robot-glb';
import './robot-meshes.css';

type Vec3 = [number, number, number];

interface VisualJson {
  file: string;
  xyz: Vec3;
  rpy: Vec3;
  scale: Vec3;
}

interface JointJson {
  name: string;
  type: 'revolute' | 'continuous' | 'prismatic' | 'fixed' | 'floating' | 'planar';
  parent: string;
  child: string;
  xyz: Vec3;
  rpy: Vec3;
  axis: Vec3;
  mimic?: { joint: string; multiplier: number; offset: number };
}

interface RobotJson {
  name: string;
  links: { name: string; visuals: VisualJson[] }[];
  joints: JointJson[];
}

/** A URDF `rpy` (fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)) as a quaternion. */
function rpyQuaternion([r, p, y]: Vec3): THREE.Quaternion {
  return new THREE.Quaternion().setFromEuler(new THREE.Euler(r, p, y, 'ZYX'));
}

/** Where a drawn robot is (world frame), for the browser tests. */
export interface MeshPlacement {
  /** Each link frame's origin, by URDF link name. */
  links: Record<string, Vec3>;
  /** The hand's TCP frame (URDF `panda_hand_tcp`): origin and z (approach) axis. */
  tcp: { position: Vec3; z: Vec3 } | null;
  /** Centres of the finger meshes' bounding boxes (URDF `panda_leftfinger`, `panda_rightfinger`). */
  fingers: Vec3[];
}

/** A robot's tree and its loaded link meshes, shared by every arm drawn with it. */
export class RobotModel {
  /** Geometries and materials of the meshes: every instance borrows them, none frees them. */
  readonly shared = new Set<unknown>();

  private constructor(
    private readonly tree: RobotJson,
    private readonly meshes: Map<string, GlbMesh[]>,
  ) {
    for (const list of meshes.values()) {
      for (const m of list) {
        this.shared.add(m.geometry);
        this.shared.add(m.material);
      }
    }
  }

  /** Loads `robot.json` and every link mesh of the robot in folder `base` (a URL ending in `/`). */
  static async load(base: URL): Promise<RobotModel> {
    const at = new URL('robot.json', base);
    const res = await fetch(at);
    if (!res.ok) throw new Error(`${at.pathname}: HTTP ${res.status}`);
    const tree = (await res.json()) as RobotJson;
    if (!Array.isArray(tree.links) || !Array.isArray(tree.joints)) throw new Error(`${at.pathname}: expected "links" and "joints" arrays`);
    await MeshoptDecoder.ready;
    const files = [...new Set(tree.links.flatMap((l) => l.visuals.map((v) => v.file)))];
    const meshes = new Map<string, GlbMesh[]>();
    await Promise.all(
      files.map(async (f) => {
        const url = new URL(f, base);
        const r = await fetch(url);
        if (!r.ok) throw new Error(`${url.pathname}: HTTP ${r.status}`);
        meshes.set(f, readGlb(new Uint8Array(await r.arrayBuffer()), f, MeshoptDecoder));
      }),
    );
    // A tree that does not hold together fails here, not while a frame is drawn.
    new RobotInstance(tree, meshes, false);
    return new RobotModel(tree, meshes);
  }

  /** The robot's joint angles: its revolute joints that move on their own. */
  get dof(): number {
    return this.tree.joints.filter((j) => (j.type === 'revolute' || j.type === 'continuous') && !j.mimic).length;
  }

  /** A new drawing of the robot (its meshes borrowed), at zero joint angles. */
  instantiate(shadows: boolean): RobotInstance {
    return new RobotInstance(this.tree, this.meshes, shadows);
  }
}

/** One drawn robot: a group per link, placed by its joint from its parent link. */
export class RobotInstance {
  /** The root link's group; placed at the arm's base pose. */
  readonly root: THREE.Group;
  /** Each link's group by URDF name (its world matrix is the link frame). */
  readonly links = new Map<string, THREE.Object3D>();
  /** Each moving joint's group (its parent holds the joint's origin) with type and axis. */
  private readonly joints = new Map<string, { node: THREE.Object3D; type: JointJson['type']; axis: THREE.Vector3; mimic?: JointJson['mimic'] }>();
  /** The revolute joints that move on their own, in file order: the arm's joint angles. */
  readonly revolute: string[] = [];
  /** The prismatic joints that move on their own (the gripper's fingers). */
  readonly prismatic: string[] = [];

  constructor(tree: RobotJson, meshes: Map<string, GlbMesh[]>, shadows: boolean) {
    for (const l of tree.links) {
      const g = new THREE.Group();
      g.name = l.name;
      for (const v of l.visuals) {
        const holder = new THREE.Group();
        holder.position.set(...v.xyz);
        holder.quaternion.copy(rpyQuaternion(v.rpy));
        holder.scale.set(...v.scale);
        for (const m of meshes.get(v.file) ?? []) {
          const c = new THREE.Mesh(m.geometry, m.material);
          // The glTF node's transform: it turns the quantised positions back into metres.
          m.matrix.decompose(c.position, c.quaternion, c.scale);
          c.castShadow = shadows;
          c.receiveShadow = shadows;
          c.userData.visual = v.file;
          holder.add(c);
        }
        g.add(holder);
      }
      this.links.set(l.name, g);
    }
    const children = new Set<string>();
    for (const j of tree.joints) {
      const parent = this.links.get(j.parent);
      const child = this.links.get(j.child);
      if (!parent || !child) throw new Error(`robot.json: joint ${j.name} joins unknown link ${parent ? j.child : j.parent}`);
      const origin = new THREE.Group();
      origin.name = `${j.name}:origin`;
      origin.position.set(...j.xyz);
      origin.quaternion.copy(rpyQuaternion(j.rpy));
      origin.add(child);
      parent.add(origin);
      children.add(j.child);
      if (j.type === 'fixed') continue;
      this.joints.set(j.name, { node: child, type: j.type, axis: new THREE.Vector3(...j.axis).normalize(), mimic: j.mimic });
      if (j.mimic) continue;
      if (j.type === 'revolute' || j.type === 'continuous') this.revolute.push(j.name);
      else if (j.type === 'prismatic') this.prismatic.push(j.name);
    }
    const roots = tree.links.filter((l) => !children.has(l.name));
    if (roots.length !== 1) throw new Error(`robot.json: expected one root link, found ${roots.map((l) => l.name).join(', ') || 'none'}`);
    this.root = new THREE.Group();
    this.root.name = `robot:${tree.name}`;
    this.root.add(this.links.get(roots[0].name)!);
  }

  /**
   * Poses the robot: the revolute joints take `angles` in order (rad), every free prismatic joint
   * takes `slide` (m); mimic joints follow theirs.
   */
  pose(angles: readonly number[], slide: number): void {
    const values = new Map<string, number>();
    this.revolute.forEach((n, i) => values.set(n, angles[i] ?? 0));
    for (const n of this.prismatic) values.set(n, slide);
    for (const [name, j] of this.joints) {
      const q = j.mimic ? (values.get(j.mimic.joint) ?? 0) * j.mimic.multiplier + j.mimic.offset : (values.get(name) ?? 0);
      if (j.type === 'prismatic') j.node.position.copy(j.axis).multiplyScalar(q);
      else if (j.type === 'revolute' || j.type === 'continuous') j.node.quaternion.setFromAxisAngle(j.axis, q);
    }
  }

  /** Where the links, the TCP frame and the fingers are drawn now (world frame). */
  placement(): MeshPlacement {
    const v = (p: THREE.Vector3): Vec3 => [p.x, p.y, p.z];
    this.root.updateWorldMatrix(true, true);
    const links: Record<string, Vec3> = {};
    for (const [name, o] of this.links) links[name] = v(o.getWorldPosition(new THREE.Vector3()));
    const t = this.links.get('panda_hand_tcp');
    const fingers = ['panda_leftfinger', 'panda_rightfinger'].flatMap((n) => {
      const f = this.links.get(n);
      return f ? [v(new THREE.Box3().setFromObject(f).getCenter(new THREE.Vector3()))] : [];
    });
    const tcp = t ? { position: v(t.getWorldPosition(new THREE.Vector3())), z: v(new THREE.Vector3(0, 0, 1).transformDirection(t.matrixWorld)) } : null;
    return { links, tcp, fingers };
  }
}

/** The view's "Capsules / Meshes" switch: two toggle buttons over the 3-D view's corner. */
export function armStyleSwitch(host: HTMLElement, style: 'meshes' | 'capsules', onChange: (s: 'meshes' | 'capsules') => void): HTMLElement {
  const make = (s: 'meshes' | 'capsules', text: string, title: string) => {
    const b = el('button', { type: 'button', id: `arm-${s}`, title, 'aria-pressed': String(s === style) }, text);
    b.addEventListener('click', () => {
      for (const x of root.querySelectorAll('button')) x.setAttribute('aria-pressed', String(x === b));
      onChange(s);
    });
    return b;
  };
  const root = el(
    'div',
    { class: 'arm-style', role: 'group', 'aria-label': 'How the arms are drawn' },
    make('capsules', 'Capsules', 'Draw the arms as the simulator sees them: link capsules and finger boxes'),
    make('meshes', 'Meshes', "Draw the arms with the robot's own meshes, posed from the joint angles"),
  );
  host.appendChild(root);
  return root;
}
