// The page's robot meshes (web/public/robots/<robot>/, written by scripts/robot-meshes/convert.mjs) agree
// with what they were made from: the Panda's robot.json carries the vendored URDF's joints and
// visuals as they are now (a URDF edited without running `npm run robot-meshes` fails here), and
// every mesh file it names is there, a meshopt-compressed glTF binary of the recorded size.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { DOMParser } from '@xmldom/xmldom';

const root = new URL('../../', import.meta.url);
const read = (path) => readFileSync(new URL(path, root));
const ROBOTS = ['panda', 'ur5'];

const nums = (s, fallback) => (s || fallback).trim().split(/\s+/).map(Number);
const children = (el, tag) => {
  const out = [];
  for (let c = el.firstChild; c; c = c.nextSibling) if (c.nodeType === 1 && c.nodeName === tag) out.push(c);
  return out;
};

describe('robot meshes of the page', () => {
  test("the Panda's robot.json carries the vendored URDF's joints and visuals", () => {
    const json = JSON.parse(read('web/public/robots/panda/robot.json').toString());
    const urdf = new DOMParser().parseFromString(read('robots/example-robot-data/robots/panda_description/urdf/panda.urdf').toString(), 'text/xml');
    const robot = urdf.documentElement;
    const joints = children(robot, 'joint').map((j) => {
      const o = children(j, 'origin')[0];
      return {
        name: j.getAttribute('name'),
        type: j.getAttribute('type'),
        parent: children(j, 'parent')[0].getAttribute('link'),
        child: children(j, 'child')[0].getAttribute('link'),
        xyz: nums(o?.getAttribute('xyz'), '0 0 0'),
        rpy: nums(o?.getAttribute('rpy'), '0 0 0'),
        axis: nums(children(j, 'axis')[0]?.getAttribute('xyz'), '1 0 0'),
      };
    });
    assert.deepEqual(
      json.joints.map(({ name, type, parent, child, xyz, rpy, axis }) => ({ name, type, parent, child, xyz, rpy, axis })),
      joints,
    );
    const visuals = children(robot, 'link').map((l) => ({
      name: l.getAttribute('name'),
      files: children(l, 'visual').map((v) => children(children(v, 'geometry')[0], 'mesh')[0].getAttribute('filename').replace(/^.*\//, '').replace(/\.dae$/, '.glb')),
    }));
    assert.deepEqual(json.links.map((l) => ({ name: l.name, files: l.visuals.map((v) => v.file) })), visuals);
    // The arm the simulator models: seven revolute joints, two prismatic fingers (one mimics).
    const moving = json.joints.filter((j) => j.type !== 'fixed');
    assert.equal(moving.filter((j) => j.type === 'revolute').length, 7);
    assert.deepEqual(moving.filter((j) => j.type === 'prismatic').map((j) => !!j.mimic), [false, true]);
  });

  for (const robot of ROBOTS) {
    test(`${robot}: every mesh robot.json names is a compressed glb of the recorded size, with the licence`, () => {
      const json = JSON.parse(read(`web/public/robots/${robot}/robot.json`).toString());
      const named = new Set(json.links.flatMap((l) => l.visuals.map((v) => v.file)));
      assert.deepEqual([...named].sort(), Object.keys(json.files).sort());
      for (const [file, info] of Object.entries(json.files)) {
        const b = read(`web/public/robots/${robot}/${file}`);
        assert.equal(b.length, info.bytes, `${file}: size`);
        assert.equal(b.readUInt32LE(0), 0x46546c67, `${file}: glTF magic`);
        assert.equal(b.readUInt32LE(4), 2, `${file}: glTF version`);
        const gltf = JSON.parse(b.subarray(20, 20 + b.readUInt32LE(12)).toString());
        assert.deepEqual(gltf.extensionsRequired.sort(), ['EXT_meshopt_compression', 'KHR_mesh_quantization'], file);
        assert.ok(info.triangles > 0 && info.triangles <= info.sourceTriangles, `${file}: ${info.triangles} of ${info.sourceTriangles} triangles`);
      }
      assert.ok(read(`web/public/robots/${robot}/LICENSE`).length > 1000, 'the licence is beside the meshes');
    });
  }
});
