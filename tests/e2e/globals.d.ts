// The page's test hooks (web/src/test-hooks.ts `window.lfd`), as the browser tests see them.
import type { ArmSnapshot, Frame } from '../../pkg/web/logic_lfd.js';

type Vec3 = [number, number, number];

declare global {
  interface Window {
    lfd: {
      frame: () => Frame | null;
      screenPosition: (body: string) => { x: number; y: number } | null;
      project: (p: [number, number, number]) => { x: number; y: number };
      stepTimes: () => number[];
      replans: () => [number, number][];
      setPddl: (domain: string, problem: string, demo?: string) => Promise<void>;
      renderMs: () => number;
      lastCancel: () => { clickedAt: number; appliedAt: number; repliedAt: number } | null;
      memory: () => Promise<{ wasmBytes: number; freshBytes: number; geometries: number; textures: number }>;
      loadedAt: number;
      moveMarks: () => string[];
      marks: () => { kind: string; t: number; text: string; ms?: number }[];
      chartMarks: () => { kind: string; t: number; text: string }[][];
      viewing: () => { t: number | null; end: number };
      bodyPosition: (body: string) => [number, number, number] | null;
      rewind?: () => { moments: number; recorded: number; snapshots: number; plans: number; replans: number };
      speedUp: () => Promise<{ stage: string; warmReplans: number; moved: number; reason: string }>;
      armMeshes: () => {
        style: 'meshes' | 'capsules';
        loaded: boolean;
        arms: ({
          name: string;
          shown: boolean;
          drawn: ArmSnapshot;
          links: Record<string, Vec3>;
          tcp: { position: Vec3; z: Vec3 } | null;
          fingers: Vec3[];
        } | null)[];
      };
    };
  }
}
