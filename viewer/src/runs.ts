// The studio's runs list (`api/studio/runs`, newest first): each run's
// name, job, state and line; a click shows it, two ticked are compared side
// by side (`openCompare`).
import { esc } from './view2d';

/** A run as `api/studio/runs` lists it. */
export interface RunEntry {
  name: string;
  job: string | null;
  kind: string | null;
  state: string;
  line: string | null;
}

/** The list in `host`: `show(name)` on a click, `compare(a, b)` for two ticked. */
export class RunsList {
  private runs: RunEntry[] = [];
  private ticked: string[] = [];
  private list: HTMLElement;
  private button: HTMLButtonElement;
  private current: string | null = null;

  constructor(host: HTMLElement, private show: (name: string) => void, private compare: (names: string[]) => void) {
    host.innerHTML = `<h2>Runs <button type="button" class="compare" disabled
      title="Tick two runs to compare them side by side">compare</button></h2><ul class="runs"></ul>`;
    this.list = host.querySelector('ul') as HTMLElement;
    this.button = host.querySelector('button.compare') as HTMLButtonElement;
    this.button.addEventListener('click', () => {
      if (this.ticked.length === 2) this.compare([...this.ticked]);
    });
  }

  /** The names listed, newest first. */
  names(): string[] {
    return this.runs.map((r) => r.name);
  }

  /** The runs ticked for comparing. */
  selected(): string[] {
    return [...this.ticked];
  }

  /** Ticks `names` (at most two; the earlier ones dropped). */
  select(names: string[]): void {
    this.ticked = names.filter((n) => this.runs.some((r) => r.name === n)).slice(-2);
    this.draw();
  }

  /** Marks the run shown. */
  mark(name: string | null): void {
    this.current = name;
    this.draw();
  }

  /** Lists `runs`. */
  update(runs: RunEntry[]): void {
    this.runs = runs;
    this.ticked = this.ticked.filter((n) => runs.some((r) => r.name === n));
    this.draw();
  }

  private draw(): void {
    this.list.innerHTML = this.runs.length === 0
      ? '<li class="none">no runs yet</li>'
      : this.runs.map((r) => `<li data-run="${esc(r.name)}" class="${r.name === this.current ? 'current' : ''}">
          <input type="checkbox" title="Compare" ${this.ticked.includes(r.name) ? 'checked' : ''}
            ${r.state === 'done' ? '' : 'disabled'} />
          <span class="name">${esc(r.name)}</span>
          <span class="state ${esc(r.state)}">${esc(r.state)}</span>
          <div class="line">${esc(r.line ?? '')}</div></li>`).join('');
    for (const li of this.list.querySelectorAll<HTMLElement>('li[data-run]')) {
      const name = li.dataset.run ?? '';
      const box = li.querySelector('input') as HTMLInputElement;
      box.addEventListener('change', () => {
        this.select(box.checked ? [...this.ticked.filter((n) => n !== name), name] : this.ticked.filter((n) => n !== name));
      });
      li.addEventListener('click', (e) => {
        if (e.target === box) return;
        const run = this.runs.find((r) => r.name === name);
        if (run?.state === 'done') this.show(name);
      });
    }
    this.button.disabled = this.ticked.length !== 2;
  }
}
