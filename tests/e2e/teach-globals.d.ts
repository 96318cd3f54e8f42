// The Teach mode's test hooks (web/src/teach.ts `window.lfdTeach`), as the browser tests see them.
import type { TaughtInfo, TeachState } from '../../pkg/web/logic_lfd.js';

declare global {
  interface Window {
    lfdTeach: {
      state: () => TeachState | null;
      info: () => TaughtInfo | null;
      demoJson: () => string | null;
      handle: (part: 'move' | 'lift' | 'turn') => { x: number; y: number };
      busy: () => boolean;
      /** The drop marks while a block is dragged: the receiving block and the footprint's centre. */
      dropHint: () => { body: string; onto: string | null; shadow: [number, number, number] } | null;
    };
  }
}
