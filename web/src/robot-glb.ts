/**
 * Reads the glTF binaries scripts/robot-meshes/convert.mjs writes (meshes, quantised attributes
 * (KHR_mesh_quantization), meshopt-compressed buffer views (EXT_meshopt_compression), plain
 * colour materials) into three.js geometries. three's GLTFLoader reads them too, but it would
 * pull parts of three.js the page does not otherwise use into its first-load bundle.
 */
import * as THREE from 'three';

/** One primitive of a glb: geometry, material and the transform of its node. */
export interface GlbMesh {
  geometry: THREE.BufferGeometry;
  material: THREE.MeshStandardMaterial;
  matrix: THREE.Matrix4;
}

/** The part of meshoptimizer's decoder used here. */
export interface MeshoptDecoderLike {
  decodeGltfBuffer(target: Uint8Array, count: number, size: number, source: Uint8Array, mode: string, filter?: string): void;
}

interface Gltf {
  accessors?: { bufferView?: number; byteOffset?: number; componentType: number; count: number; type: string; normalized?: boolean }[];
  bufferViews?: {
    buffer: number;
    byteOffset?: number;
    byteLength: number;
    byteStride?: number;
    extensions?: { EXT_meshopt_compression?: { buffer: number; byteOffset?: number; byteLength: number; byteStride: number; count: number; mode: string; filter?: string } };
  }[];
  materials?: { pbrMetallicRoughness?: { baseColorFactor?: number[]; metallicFactor?: number; roughnessFactor?: number } }[];
  meshes?: { primitives: { attributes: Record<string, number>; indices?: number; material?: number; mode?: number }[] }[];
  nodes?: { mesh?: number; matrix?: number[]; translation?: number[]; rotation?: number[]; scale?: number[]; children?: number[] }[];
  scenes?: { nodes?: number[] }[];
  scene?: number;
}

const COMPONENTS: Record<number, Int8ArrayConstructor | Uint8ArrayConstructor | Int16ArrayConstructor | Uint16ArrayConstructor | Uint32ArrayConstructor | Float32ArrayConstructor> = {
  5120: Int8Array,
  5121: Uint8Array,
  5122: Int16Array,
  5123: Uint16Array,
  5125: Uint32Array,
  5126: Float32Array,
};
const SIZES: Record<string, number> = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };
const ATTRIBUTES: Record<string, string> = { POSITION: 'position', NORMAL: 'normal' };

/** The meshes of glb `bytes` (named `file` in errors), in the frame of the glb's scene. */
export function readGlb(bytes: Uint8Array, file: string, decoder: MeshoptDecoderLike): GlbMesh[] {
  const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const fail = (what: string): never => {
    throw new Error(`${file}: ${what}`);
  };
  if (bytes.length < 20 || dv.getUint32(0, true) !== 0x46546c67 || dv.getUint32(4, true) !== 2) fail('not a glTF 2.0 binary');
  const jsonLength = dv.getUint32(12, true);
  if (dv.getUint32(16, true) !== 0x4e4f534a) fail('first chunk is not JSON');
  const gltf = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength))) as Gltf;
  const binAt = 20 + jsonLength;
  const bin = binAt + 8 <= bytes.length && dv.getUint32(binAt + 4, true) === 0x004e4942 ? bytes.subarray(binAt + 8, binAt + 8 + dv.getUint32(binAt, true)) : fail('no BIN chunk');

  const views = new Map<number, Uint8Array>();
  const view = (i: number): Uint8Array => {
    const known = views.get(i);
    if (known) return known;
    const v = gltf.bufferViews?.[i] ?? fail(`no bufferView ${i}`);
    const m = v.extensions?.EXT_meshopt_compression;
    let data: Uint8Array;
    if (m) {
      if (m.buffer !== 0) fail(`bufferView ${i}: compressed data outside the BIN chunk`);
      data = new Uint8Array(m.count * m.byteStride);
      const src = bin.subarray(m.byteOffset ?? 0, (m.byteOffset ?? 0) + m.byteLength);
      decoder.decodeGltfBuffer(data, m.count, m.byteStride, src, m.mode, m.filter);
    } else {
      if (v.buffer !== 0) fail(`bufferView ${i}: data outside the BIN chunk`);
      data = bin.slice(v.byteOffset ?? 0, (v.byteOffset ?? 0) + v.byteLength);
    }
    views.set(i, data);
    return data;
  };

  const accessor = (i: number): THREE.BufferAttribute => {
    const a = gltf.accessors?.[i] ?? fail(`no accessor ${i}`);
    const Ctor = COMPONENTS[a.componentType] ?? fail(`accessor ${i}: component type ${a.componentType}`);
    const size = SIZES[a.type] ?? fail(`accessor ${i}: type ${a.type}`);
    if (a.bufferView === undefined) fail(`accessor ${i}: no bufferView`);
    const data = view(a.bufferView!);
    const stride = gltf.bufferViews![a.bufferView!].byteStride ?? size * Ctor.BYTES_PER_ELEMENT;
    const out = new Ctor(a.count * size);
    // Copied element by element: the views may be interleaved or padded (quantised VEC3s are).
    const src = new DataView(data.buffer, data.byteOffset, data.byteLength);
    const get = getter(src, a.componentType);
    const bytes = Ctor.BYTES_PER_ELEMENT;
    for (let k = 0; k < a.count; k++) {
      const at = (a.byteOffset ?? 0) + k * stride;
      for (let c = 0; c < size; c++) out[k * size + c] = get(at + c * bytes);
    }
    return new THREE.BufferAttribute(out, size, !!a.normalized);
  };

  const materials = (gltf.materials ?? []).map((m) => {
    const p = m.pbrMetallicRoughness ?? {};
    const [r, g, b, alpha] = p.baseColorFactor ?? [1, 1, 1, 1];
    return new THREE.MeshStandardMaterial({
      color: new THREE.Color().setRGB(r, g, b, THREE.LinearSRGBColorSpace),
      metalness: p.metallicFactor ?? 1,
      roughness: p.roughnessFactor ?? 1,
      transparent: alpha < 1,
      opacity: alpha,
    });
  });
  const fallback = new THREE.MeshStandardMaterial();

  const out: GlbMesh[] = [];
  const visit = (n: number, parent: THREE.Matrix4) => {
    const node = gltf.nodes?.[n] ?? fail(`no node ${n}`);
    const local = node.matrix
      ? new THREE.Matrix4().fromArray(node.matrix)
      : new THREE.Matrix4().compose(
          new THREE.Vector3().fromArray(node.translation ?? [0, 0, 0]),
          new THREE.Quaternion().fromArray(node.rotation ?? [0, 0, 0, 1]),
          new THREE.Vector3().fromArray(node.scale ?? [1, 1, 1]),
        );
    const matrix = parent.clone().multiply(local);
    if (node.mesh !== undefined) {
      const mesh = gltf.meshes?.[node.mesh] ?? fail(`no mesh ${node.mesh}`);
      for (const p of mesh.primitives) {
        if ((p.mode ?? 4) !== 4) fail(`mesh ${node.mesh}: only triangles are read`);
        const geometry = new THREE.BufferGeometry();
        for (const [semantic, i] of Object.entries(p.attributes)) {
          if (ATTRIBUTES[semantic]) geometry.setAttribute(ATTRIBUTES[semantic], accessor(i));
        }
        if (!geometry.getAttribute('position')) fail(`mesh ${node.mesh}: a primitive without positions`);
        if (p.indices !== undefined) geometry.setIndex(accessor(p.indices));
        if (!geometry.getAttribute('normal')) geometry.computeVertexNormals();
        out.push({ geometry, material: p.material === undefined ? fallback : materials[p.material], matrix });
      }
    }
    for (const c of node.children ?? []) visit(c, matrix);
  };
  for (const n of gltf.scenes?.[gltf.scene ?? 0]?.nodes ?? []) visit(n, new THREE.Matrix4());
  if (!out.length) fail('no mesh');
  return out;
}

function getter(dv: DataView, type: number): (at: number) => number {
  switch (type) {
    case 5120:
      return (at) => dv.getInt8(at);
    case 5121:
      return (at) => dv.getUint8(at);
    case 5122:
      return (at) => dv.getInt16(at, true);
    case 5123:
      return (at) => dv.getUint16(at, true);
    case 5125:
      return (at) => dv.getUint32(at, true);
    default:
      return (at) => dv.getFloat32(at, true);
  }
}
