// Where a frame's time goes, for measuring (never shown): the time spent in
// each phase of the animation loop, summed over the frames since the last
// reset, and the intervals between animation frames. `window.formcamPerf`
// lets the browser test read it.

/** The phases of a frame, in their order. */
export const PHASES = [
  'sample',
  'poses',
  'band',
  'checks',
  'readouts',
  'program',
  'plots',
  'controls',
  'render',
] as const;

export type Phase = (typeof PHASES)[number];

/** What `window.formcamPerf.report()` returns. */
export interface PerfReport {
  /** Animation frames seen, and of them frames drawn. */
  frames: number;
  drawn: number;
  /** Seconds since the reset. */
  seconds: number;
  /** Mean ms per animation frame spent in each phase (script time only). */
  ms_per_frame: Record<Phase | 'script', number>;
  /** Mean ms between animation frames. */
  interval_ms: number;
}

export interface PerfProbe {
  reset(): void;
  report(): PerfReport;
  /** Draws nothing but the background (the floor of a frame's cost), or everything again. */
  bare(on: boolean): void;
}

declare global {
  interface Window { formcamPerf?: PerfProbe }
}

export class FrameClock {
  private readonly total = new Map<Phase, number>();
  private frames = 0;
  private drawn = 0;
  private since = performance.now();
  private lapAt = 0;
  /** Within a frame: laps outside one (a seek's answer) are not counted. */
  private open = false;

  constructor() {
    this.reset();
  }

  reset(): void {
    for (const p of PHASES) this.total.set(p, 0);
    this.frames = 0;
    this.drawn = 0;
    this.since = performance.now();
  }

  /** An animation frame starts. */
  begin(): void {
    this.frames++;
    this.open = true;
    this.lapAt = performance.now();
  }

  /** The frame ends. */
  end(): void {
    this.open = false;
  }

  /** The time since the last lap (or the frame's start) goes to `phase`. */
  lap(phase: Phase): void {
    if (!this.open) return;
    const now = performance.now();
    this.total.set(phase, (this.total.get(phase) ?? 0) + now - this.lapAt);
    this.lapAt = now;
  }

  /** A frame was drawn. */
  draw(): void {
    this.drawn++;
  }

  report(): PerfReport {
    const n = Math.max(this.frames, 1);
    const seconds = (performance.now() - this.since) / 1000;
    const ms = {} as Record<Phase | 'script', number>;
    let script = 0;
    for (const p of PHASES) {
      const v = (this.total.get(p) ?? 0) / n;
      ms[p] = v;
      script += v;
    }
    ms.script = script;
    return { frames: this.frames, drawn: this.drawn, seconds, ms_per_frame: ms, interval_ms: (1000 * seconds) / n };
  }
}
