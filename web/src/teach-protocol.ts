/**
 * The Teach mode's requests to the worker (merged into the page's `Api` in protocol.ts): a
 * `Teacher` (the demonstration recorder) lives in the same worker as the Session, and "Run"
 * replaces the Session by one running the taught task.
 */
import type { Benchmark, Frame, TaughtFolder, TaughtInfo, TaughtRunOptions, TeachEdit, TeachFinish, TeachResult, TeachState } from 'logic-lfd';

export interface TeachApi {
  /** Starts fetching Teach mode's wasm module (the tab opened), so that Record need not wait. */
  teachLoad: { args: Record<string, never>; result: null };
  /** Records in the benchmark's workcell, or in the task folder's when one is given. */
  teachStart: { args: { benchmark: Benchmark; folder?: TaughtFolder }; result: TeachState };
  teachPush: { args: { edit: TeachEdit }; result: TeachResult };
  teachUndo: { args: Record<string, never>; result: TeachResult };
  teachFinish: { args: Record<string, never>; result: TeachFinish };
  teachRecording: { args: Record<string, never>; result: string };
  /** `folder`: the task folder the demo was taught in (none: a benchmark's workcell). */
  teachInfo: { args: { demoJson: string; folder?: TaughtFolder }; result: TaughtInfo };
  teachRun: { args: { demoJson: string; options: TaughtRunOptions; folder?: TaughtFolder }; result: Frame };
  teachClose: { args: Record<string, never>; result: null };
}
