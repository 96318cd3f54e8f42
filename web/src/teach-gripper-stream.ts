/**
 * Sends the gripper handle's poses to the recorder one at a time: while one is in flight only the
 * latest pose waits (a final one, the end of a drag or a grip change, stays final), so a fast drag
 * never queues up. Each sample lasts the wall time since the previous one, bounded, so a slow drag
 * records a slow motion.
 */
import type { HandlePose } from './teach-gripper';

/** Recorded duration of one sample (s): a final sample, and the bounds of the others. */
const FINAL_S = 0.5;
const MIN_S = 0.05;
const MAX_S = 0.3;

export interface GripperStreamSink {
  /** Records the handle at `pose` for `duration` seconds. */
  send: (pose: HandlePose, duration: number) => Promise<unknown>;
  /** A send failed. */
  report: (message: string) => void;
  /** The last final pose was recorded and nothing waits. */
  settled: () => void;
}

export class GripperStream {
  private inflight = false;
  private pending: { pose: HandlePose; final: boolean } | null = null;
  private lastSend = 0;

  constructor(private readonly sink: GripperStreamSink) {}

  /** Whether a sample is being recorded. */
  get sending(): boolean {
    return this.inflight;
  }

  /** Whether a sample is being recorded or waits. */
  get busy(): boolean {
    return this.inflight || this.pending !== null;
  }

  /** Drops the waiting sample. */
  clear(): void {
    this.pending = null;
  }

  queue(pose: HandlePose, final: boolean): void {
    this.pending = { pose, final: final || (this.pending?.final ?? false) };
    void this.pump();
  }

  private async pump(): Promise<void> {
    if (this.inflight || !this.pending) return;
    const { pose, final } = this.pending;
    this.pending = null;
    this.inflight = true;
    const now = performance.now();
    const duration = final ? FINAL_S : Math.min(MAX_S, Math.max(MIN_S, (now - (this.lastSend || now)) / 1000));
    this.lastSend = now;
    try {
      await this.sink.send(pose, duration);
    } catch (e) {
      this.sink.report((e as Error).message);
    } finally {
      this.inflight = false;
    }
    if (this.pending) void this.pump();
    else if (final) {
      this.lastSend = 0;
      this.sink.settled();
    }
  }
}
