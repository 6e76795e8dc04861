// The program text: only the rows in sight are in the page (programs run
// to 10^5 lines and more), the same row elements reused as it scrolls; a
// click on a line asks to go there. Marking the line shown while playing
// reads no layout: the box's height and scroll position are kept here.
const ROW = 16;
/** Rows drawn beyond each edge of the box. */
const MARGIN = 5;

export class ProgramView {
  private readonly lines: string[];
  private readonly spacer = document.createElement('div');
  /** The row elements drawn, lines `first + 1 ...`. */
  private readonly rows: HTMLDivElement[] = [];
  private first = -1;
  private current = 0;
  /** The box's height and scroll position, px (as last read or set). */
  private height: number;
  private top = 0;

  constructor(
    private readonly host: HTMLElement,
    text: string,
    private readonly onPick: (line: number) => void,
  ) {
    this.lines = text.split('\n');
    if (this.lines.length > 0 && this.lines[this.lines.length - 1] === '') this.lines.pop();
    this.spacer.style.height = `${this.lines.length * ROW}px`;
    host.appendChild(this.spacer);
    this.height = host.clientHeight;
    host.addEventListener('scroll', () => {
      this.top = host.scrollTop;
      this.draw();
    });
    new ResizeObserver(() => {
      this.height = host.clientHeight;
      this.draw();
    }).observe(host);
    host.addEventListener('click', (e) => {
      const row = (e.target as HTMLElement).closest('.row') as HTMLElement | null;
      if (row?.dataset.line) this.onPick(Number(row.dataset.line));
    });
    this.draw();
  }

  /** Marks `line` (1-based) and scrolls it into sight. */
  mark(line: number): void {
    if (line === this.current) return;
    this.current = line;
    const top = (line - 1) * ROW;
    if (top < this.top || top > this.top + this.height - ROW) {
      this.top = Math.max(0, Math.min(top - this.height / 2, this.lines.length * ROW - this.height));
      this.host.scrollTop = this.top;
    }
    this.draw();
  }

  /** The rows in sight: their text when the first one changed, the mark always. */
  private draw(): void {
    const first = Math.max(0, Math.floor(this.top / ROW) - MARGIN);
    const count = Math.max(0, Math.min(this.lines.length - first, Math.ceil(this.height / ROW) + 2 * MARGIN));
    if (first !== this.first || count !== this.rows.length) {
      this.first = first;
      while (this.rows.length < count) this.rows.push(this.spacer.appendChild(newRow()));
      while (this.rows.length > count) this.rows.pop()?.remove();
      this.rows.forEach((row, k) => {
        const i = first + k;
        row.style.top = `${i * ROW}px`;
        row.dataset.line = String(i + 1);
        (row.firstChild as HTMLElement).textContent = String(i + 1);
        (row.lastChild as Text).data = this.lines[i];
      });
    }
    this.rows.forEach((row, k) => {
      const current = this.first + k + 1 === this.current;
      if (row.classList.contains('current') !== current) row.classList.toggle('current', current);
    });
  }
}

/** A row: the line's number, then its text. */
function newRow(): HTMLDivElement {
  const row = document.createElement('div');
  row.className = 'row';
  const n = document.createElement('span');
  n.className = 'n';
  row.append(n, document.createTextNode(''));
  return row;
}
