// The program text: only the rows in sight are in the page (programs run
// to 10^5 lines and more); a click on a line asks to go there.
const ROW = 16;

export class ProgramView {
  private readonly lines: string[];
  private readonly spacer = document.createElement('div');
  private current = 0;

  constructor(
    private readonly host: HTMLElement,
    text: string,
    private readonly onPick: (line: number) => void,
  ) {
    this.lines = text.split('\n');
    if (this.lines.length > 0 && this.lines[this.lines.length - 1] === '') this.lines.pop();
    this.spacer.style.height = `${this.lines.length * ROW}px`;
    host.appendChild(this.spacer);
    host.addEventListener('scroll', () => this.draw());
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
    const h = this.host.clientHeight;
    if (top < this.host.scrollTop || top > this.host.scrollTop + h - ROW) {
      this.host.scrollTop = Math.max(0, top - h / 2);
    }
    this.draw();
  }

  private draw(): void {
    const first = Math.max(0, Math.floor(this.host.scrollTop / ROW) - 5);
    const last = Math.min(this.lines.length, first + Math.ceil(this.host.clientHeight / ROW) + 10);
    this.spacer.replaceChildren();
    for (let i = first; i < last; i++) {
      const row = document.createElement('div');
      row.className = i + 1 === this.current ? 'row current' : 'row';
      row.style.top = `${i * ROW}px`;
      row.dataset.line = String(i + 1);
      const n = document.createElement('span');
      n.className = 'n';
      n.textContent = String(i + 1);
      row.append(n, this.lines[i]);
      this.spacer.appendChild(row);
    }
  }
}
