import { View } from './view';
const q = (x: number, y: number, z: number, w: number) => [x, y, z, w] as [number, number, number, number];
const id = q(0, 0, 0, 1);
const blk = (name: string, color: string, p: [number, number, number]) => ({ name, kind: 'block' as const, color, shape: { type: 'cuboid' as const, half_extents: [0.03, 0.03, 0.03] as [number, number, number] }, pose: { position: p, quaternion: id } });
const chain: [number, number, number][] = [[0, 0, 0.02], [0, 0, 0.333], [0.0, 0, 0.65], [0.25, 0, 0.72], [0.42, 0, 0.55], [0.5, 0, 0.35], [0.5, 0, 0.22]];
const snap = {
  version: 1, name: 'b1-tower', time: 0, dt: 0.01, floor_z: -0.75, predicates: [], regions: [{ name: 'left', min: [0.3, -0.4], max: [0.7, -0.1], color: '#3e63dd' }],
  bodies: [
    { name: 'table', kind: 'table' as const, color: '#6b5a45', shape: { type: 'cuboid' as const, half_extents: [0.5, 0.6, 0.02] as [number, number, number] }, pose: { position: [0.45, 0, -0.02] as [number, number, number], quaternion: id } },
    { name: 'hook', kind: 'hook' as const, color: '#8e4ec6', shape: { type: 'compound' as const, parts: [{ pose: { position: [0, 0, 0] as [number, number, number], quaternion: id }, half_extents: [0.15, 0.01, 0.01] as [number, number, number] }, { pose: { position: [0.14, 0.04, 0] as [number, number, number], quaternion: id }, half_extents: [0.01, 0.05, 0.01] as [number, number, number] }] }, pose: { position: [0.3, 0.35, 0.01] as [number, number, number], quaternion: id } },
    blk('a', '#e5484d', [0.5, -0.2, 0.03]), blk('b', '#46a758', [0.6, 0.1, 0.03]), blk('c', '#3e63dd', [0.6, 0.1, 0.09]), blk('d', '#ffb224', [0.4, 0.2, 0.03]),
  ],
  arms: [{ name: 'panda', base: { position: [0, 0, 0] as [number, number, number], quaternion: id }, joints: [0, 0, 0, 0, 0, 0, 0], gripper_opening: 0.08, reach: { min_radius: 0.2, max_radius: 0.8 }, tcp: { position: [0.5, 0, 0.12] as [number, number, number], quaternion: id },
    links: chain.slice(0, -1).map((a, i) => ({ a, b: chain[i + 1], radius: i < 3 ? 0.06 : 0.045 })),
    fingers: [{ pose: { position: [0.5, -0.045, 0.16] as [number, number, number], quaternion: id }, half_extents: [0.01, 0.005, 0.025] as [number, number, number] }, { pose: { position: [0.5, 0.045, 0.16] as [number, number, number], quaternion: id }, half_extents: [0.01, 0.005, 0.025] as [number, number, number] }] }],
};
const v = new View(document.getElementById('v')!, { onDrop: async () => null });
v.update(snap as never, [{ arm: 0, pos: [0.5, 0, 0.16], target: [0.6, 0.1, 0.2] }]);
v.start();
(window as unknown as { done: boolean }).done = true;
