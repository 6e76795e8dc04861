// The checks' violations on the page: which checks ran (and why one did
// not), a list (click one to go to where it first happens), marks on the timeline bar, the axes beyond their limits
// at the time shown (red readouts) and the links a collision names.
import type { AxisHead, Sample, Violation, Violations } from './api';

/** Half a written unit: a value within it of a limit is on the limit. */
const SLACK = { mm: 0.5e-3, deg: 0.5e-4 } as Record<string, number>;

/** What a violation concerns, in words. */
function subject(v: Violation): string {
  if (v.axis) return `axis ${v.axis}`;
  if (v.links && v.links.length > 0) return v.links.join(' / ');
  return '';
}

function describe(v: Violation): string {
  const where = [
    v.block !== undefined ? `block ${v.block}` : '',
    v.line !== undefined ? `line ${v.line}` : '',
    v.time_s !== undefined ? `${v.time_s.toFixed(3)} s` : '',
  ].filter((s) => s).join(', ');
  const value = v.value !== undefined && v.limit !== undefined
    ? `: ${fmt(v.value)} ${v.unit ?? ''} (limit ${fmt(v.limit)})`
    : '';
  const count = v.count && v.count > 1 ? `, ${v.count} times` : '';
  return `${v.kind} ${subject(v)} at ${where}${value}${count}`.replace(/\s+/g, ' ').trim();
}

function fmt(x: number): string {
  return Math.abs(x) >= 1000 ? x.toFixed(1) : x.toPrecision(5);
}

/** Which checks ran and why one did not, above the list (written once). */
function ran(list: HTMLElement, data: Violations): void {
  const host = list.parentElement;
  if (!host) return;
  host.querySelectorAll('.checks, .unchecked').forEach((e) => e.remove());
  const checks = document.createElement('p');
  checks.className = 'checks';
  checks.textContent = data.source === 'check.json'
    ? 'checked when the program was written (check.json)'
    : `checked: ${(data.checks ?? []).join(', ') || 'none'}`;
  list.before(checks);
  if (data.unchecked) {
    const why = document.createElement('p');
    why.className = 'unchecked';
    why.textContent = `not checked: ${data.unchecked}`;
    list.before(why);
  }
}

export class ViolationView {
  constructor(
    list: HTMLElement,
    marks: HTMLElement,
    private readonly data: Violations,
    duration: number,
    seek: (t: number) => void,
  ) {
    list.replaceChildren();
    ran(list, data);
    if (data.violations.length === 0) {
      const li = document.createElement('li');
      li.className = 'clean';
      li.textContent = data.source === 'check.json' ? 'clean (check.json)' : 'clean';
      list.appendChild(li);
    }
    for (const v of data.violations) {
      const li = document.createElement('li');
      li.textContent = describe(v);
      li.dataset.kind = v.kind;
      const t = v.time_s;
      if (t !== undefined) {
        li.title = 'go to where it first happens';
        li.addEventListener('click', () => seek(t));
        const m = document.createElement('button');
        m.className = 'mark';
        m.title = describe(v);
        m.style.left = `${(100 * Math.min(Math.max(t / Math.max(duration, 1e-12), 0), 1)).toFixed(3)}%`;
        m.addEventListener('click', () => seek(t));
        marks.appendChild(m);
      }
      list.appendChild(li);
    }
  }

  /** How many violations are listed. */
  get count(): number {
    return this.data.violations.length;
  }

  /** The axes beyond a limit at the sample shown, and the links a collision there names. */
  at(s: Sample, axes: AxisHead[]): { axes: Set<string>; links: Set<string> } {
    const red = new Set<string>();
    const links = new Set<string>();
    axes.forEach((a, k) => {
      const l = this.data.limits[k];
      if (!l) return;
      const slack = SLACK[a.unit] ?? 0;
      const v = s.axes[k];
      if ((l.min !== null && v < l.min - slack) || (l.max !== null && v > l.max + slack)) red.add(a.name);
    });
    for (const v of this.data.violations) {
      if (!v.spans.some(([a, b]) => s.t >= a && s.t <= b)) continue;
      if (v.axis) red.add(v.axis);
      for (const l of v.links ?? []) links.add(l);
    }
    return { axes: red, links };
  }
}
