// Two runs of the studio side by side: their summaries in one table with
// the differences marked, their plots overlaid. (Being built: the studio's
// runs list calls `openCompare`.)

/** A run to compare: its name and the base URL its result is served at
 * (`runs/<name>/`). */
export interface RunRef { name: string; base: string }

/** What the comparison shows, for tests. */
export interface CompareState { runs: string[]; rows: number; differing: number; series: number }

/** Opens the comparison of `runs` in `host`. */
export async function openCompare(host: HTMLElement, runs: RunRef[]): Promise<CompareState> {
  host.textContent = `comparing ${runs.map((r) => r.name).join(' and ')}: not available yet`;
  return { runs: runs.map((r) => r.name), rows: 0, differing: 0, series: 0 };
}
