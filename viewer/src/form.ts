// The studio's job form, drawn from the description of the job's kind
// (`formcam-schema`'s `JobSchema` as JSON): a fieldset per table, an input
// per field by its kind (numbers, whole numbers, words as a select, a
// boolean as a checkbox, lists, lists of tables), its unit beside it, its
// range written out, its default as the placeholder and its help as the
// title. A repeated table (`[[layer]]`) has entries added and removed; a
// table the job may leave out is added or removed as a whole. Only the
// fields that apply are shown: those given, those always required, those
// required by another field's word (`radius` when `kind = "vessel"`); the
// other optional ones wait under "more". Errors are shown at their field
// (`table.field`, `layer[2].field`): a red border and the message under it.

/** A field's type (`formcam_schema::Kind`). */
export type Kind =
  | { type: 'number' | 'integer' | 'boolean' | 'text' | 'file' | 'integers' }
  | { type: 'word' | 'name' | 'number-or-word' | 'words'; of: string[] }
  | { type: 'tables'; of: Field[] };

/** One end of a range. */
export interface Bound { value: number; closed: boolean }

/** When a field is required (`formcam_schema::Condition`). */
export type Condition =
  | { when: 'is' | 'not'; field: string; words: string[] }
  | { when: 'absent'; field: string };

/** A field's default (`formcam_schema::Default`). */
export type Default =
  | { is: 'required' | 'none' }
  | { is: 'required-when'; value: Condition }
  | { is: 'value'; value: unknown }
  | { is: 'described'; value: string };

/** A field of a table. */
export interface Field {
  name: string;
  kind: Kind;
  unit: string;
  range: { min: Bound | null; max: Bound | null } | null;
  default: Default;
  help: string;
}

/** A table of a job file. */
export interface Table {
  name: string;
  repeat: 'single' | 'array';
  required: boolean;
  help: string;
  fields: Field[];
}

/** A job type's description. */
export interface JobSchema { name: string; help: string; tables: Table[] }

/** A table's values as the server sends them. */
export type TableValues = Record<string, unknown>;

/** The job as JSON: tables as objects, repeated tables as arrays of them. */
export type JobValues = Record<string, TableValues | TableValues[]>;

const UNITS: Record<string, string> = {
  none: '', mm: 'mm', deg: 'deg', s: 's', 'mm-per-min': 'mm/min', 'mm2-per-min': 'mm²/min',
};

/** A unit's symbol as the docs write it. */
export function unitSymbol(unit: string): string {
  return UNITS[unit] ?? unit;
}

/** A range as the CLI's messages write it: `> 0`, `[0, 90]`. */
export function rangeText(r: Field['range']): string {
  if (!r) return '';
  const { min, max } = r;
  if (min && max) return `${min.closed ? '[' : '('}${min.value}, ${max.value}${max.closed ? ']' : ')'}`;
  if (min) return `${min.closed ? '>=' : '>'} ${min.value}`;
  if (max) return `${max.closed ? '<=' : '<'} ${max.value}`;
  return '';
}

/** The condition in words: `when kind = vessel`. */
function conditionText(c: Condition): string {
  switch (c.when) {
    case 'is': return `when ${c.field} = ${c.words.join(' or ')}`;
    case 'not': return `unless ${c.field} = ${c.words.join(' or ')}`;
    case 'absent': return `unless ${c.field} is given`;
  }
}

/** The placeholder of an empty input: the default, or what leaving it out means. */
export function placeholder(f: Field): string {
  const d = f.default;
  switch (d.is) {
    case 'required': return 'required';
    case 'required-when': return `required ${conditionText(d.value)}`;
    case 'value': return Array.isArray(d.value) ? 'none' : String(d.value);
    case 'described': return d.value.replace(/`/g, '');
    case 'none': return '';
  }
}

/** A value as text in an input. */
function shown(v: unknown): string {
  if (v === undefined || v === null) return '';
  if (Array.isArray(v)) return v.map(String).join(', ');
  return String(v);
}

/** A number typed, or the text itself when it is none (the server words the error). */
function numberOr(text: string): number | string {
  const n = Number(text);
  return text.trim() !== '' && Number.isFinite(n) ? n : text;
}

/** An input of one field (of a table entry, or of a row of a list of tables). */
class FieldInput {
  readonly row: HTMLElement;
  private input: HTMLInputElement | HTMLSelectElement | null = null;
  private boxes: HTMLInputElement[] = [];
  private rows: HTMLElement | null = null;
  private subRows: FieldInput[][] = [];
  private message: HTMLElement;
  /** Whether the user changed it (a checkbox left alone is not written). */
  private touched = false;
  private given: boolean;

  constructor(public path: string, readonly field: Field, value: unknown, private changed: () => void) {
    this.given = value !== undefined && value !== null;
    this.row = document.createElement('div');
    this.row.className = `field kind-${field.kind.type}`;
    this.row.dataset.field = path;
    this.row.title = field.help;
    const label = document.createElement('label');
    label.className = 'name';
    label.textContent = field.name;
    const control = document.createElement('span');
    control.className = 'control';
    const unit = document.createElement('span');
    unit.className = 'unit';
    unit.textContent = unitSymbol(field.unit);
    const range = document.createElement('span');
    range.className = 'range';
    range.textContent = rangeText(field.range);
    this.message = document.createElement('div');
    this.message.className = 'message';
    this.message.hidden = true;
    this.build(control, value);
    this.label = label;
    this.row.append(label, control, unit, range, this.message);
    this.rename(path);
  }

  private label: HTMLLabelElement;

  /** Names the field by its (new) place: its rows' fields too. */
  rename(path: string): void {
    this.path = path;
    this.row.dataset.field = path;
    if (this.input) {
      this.input.id = `f-${path}`;
      this.label.htmlFor = this.input.id;
    }
    this.subRows.forEach((r, k) => {
      for (const i of r) i.rename(`${path}[${k}].${i.field.name}`);
    });
  }

  private build(control: HTMLElement, value: unknown): void {
    const k = this.field.kind;
    const mark = () => {
      this.touched = true;
      this.changed();
    };
    switch (k.type) {
      case 'boolean': {
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.checked = value === true || (value === undefined && this.field.default.is === 'value' && this.field.default.value === true);
        box.addEventListener('change', mark);
        this.input = box;
        control.append(box);
        return;
      }
      case 'word':
      case 'name': {
        const sel = document.createElement('select');
        const blank = document.createElement('option');
        blank.value = '';
        blank.textContent = placeholder(this.field) ? `(${placeholder(this.field)})` : '';
        sel.append(blank);
        const v = shown(value);
        let found = v === '';
        for (const w of k.of) {
          const o = document.createElement('option');
          o.value = w;
          o.textContent = w;
          // `name` kinds take any case: the job's spelling kept.
          if (v !== '' && w.toLowerCase() === v.toLowerCase()) {
            o.value = v;
            found = true;
          }
          sel.append(o);
        }
        if (!found) {
          const o = document.createElement('option');
          o.value = v;
          o.textContent = v;
          sel.append(o);
        }
        sel.value = v;
        sel.addEventListener('change', mark);
        this.input = sel;
        control.append(sel);
        return;
      }
      case 'words': {
        const given = Array.isArray(value) ? value.map(String) : [];
        const group = document.createElement('span');
        group.className = 'words';
        for (const w of k.of) {
          const l = document.createElement('label');
          const box = document.createElement('input');
          box.type = 'checkbox';
          box.value = w;
          box.checked = given.includes(w);
          box.addEventListener('change', mark);
          l.append(box, ` ${w}`);
          group.append(l);
          this.boxes.push(box);
        }
        control.append(group);
        return;
      }
      case 'tables': {
        this.rows = document.createElement('div');
        this.rows.className = 'rows';
        const add = document.createElement('button');
        add.type = 'button';
        add.className = 'add';
        add.textContent = `+ ${this.field.name} entry`;
        add.addEventListener('click', () => {
          this.addRow({});
          mark();
        });
        control.append(this.rows, add);
        for (const r of Array.isArray(value) ? value : []) this.addRow((r ?? {}) as TableValues);
        return;
      }
      default: {
        const input = document.createElement('input');
        if (k.type === 'number' || k.type === 'integer') {
          input.type = 'number';
          input.step = k.type === 'integer' ? '1' : 'any';
          input.inputMode = 'decimal';
        } else {
          input.type = 'text';
        }
        if (k.type === 'number-or-word') {
          const list = document.createElement('datalist');
          list.id = `words-${this.path}`;
          for (const w of k.of) {
            const o = document.createElement('option');
            o.value = w;
            list.append(o);
          }
          control.append(list);
          input.setAttribute('list', list.id);
        }
        if (k.type === 'integers') input.placeholder = 'e.g. 3, 5, 9';
        const p = placeholder(this.field);
        if (p) input.placeholder = p;
        input.value = shown(value);
        input.addEventListener('input', mark);
        this.input = input;
        control.append(input);
      }
    }
  }

  /** A row of a list of tables (`mu_segments`). */
  private addRow(values: TableValues): void {
    const fields = this.field.kind.type === 'tables' ? this.field.kind.of : [];
    const div = document.createElement('div');
    div.className = 'subrow';
    const inputs = fields.map((f) => new FieldInput(`${this.path}[${this.subRows.length}].${f.name}`, f, values[f.name], () => {
      this.touched = true;
      this.changed();
    }));
    const remove = document.createElement('button');
    remove.type = 'button';
    remove.className = 'remove';
    remove.textContent = '×';
    remove.title = 'Remove this entry';
    remove.addEventListener('click', () => {
      const k = this.subRows.indexOf(inputs);
      if (k >= 0) this.subRows.splice(k, 1);
      div.remove();
      this.rename(this.path);
      this.touched = true;
      this.changed();
    });
    div.append(...inputs.map((i) => i.row), remove);
    this.rows?.append(div);
    this.subRows.push(inputs);
  }

  /** Whether the field holds a value (one to write). */
  present(): boolean {
    return this.value() !== undefined;
  }

  /** The value to send, or undefined when the field is left out. */
  value(): unknown {
    const k = this.field.kind;
    switch (k.type) {
      case 'boolean':
        return this.given || this.touched ? (this.input as HTMLInputElement).checked : undefined;
      case 'words': {
        const on = this.boxes.filter((b) => b.checked).map((b) => b.value);
        return this.given || this.touched ? on : undefined;
      }
      case 'tables':
        return this.subRows.length > 0 || this.given || this.touched
          ? this.subRows.map((r) => Object.fromEntries(r.filter((i) => i.present()).map((i) => [i.field.name, i.value()])))
          : undefined;
    }
    const text = this.input?.value ?? '';
    if (text.trim() === '') return undefined;
    switch (k.type) {
      case 'number':
      case 'integer':
      case 'number-or-word':
        return numberOr(text);
      case 'integers':
        return text.split(/[,\s]+/).filter((t) => t !== '').map(numberOr);
      default:
        return text;
    }
  }

  /** Sets the input as a user would (events fired). */
  set(value: unknown): boolean {
    const k = this.field.kind;
    if (k.type === 'boolean' && this.input instanceof HTMLInputElement) {
      this.input.checked = value === true || value === 'true';
    } else if (k.type === 'words') {
      const on = Array.isArray(value) ? value.map(String) : shown(value).split(/[,\s]+/);
      for (const b of this.boxes) b.checked = on.includes(b.value);
    } else if (this.input instanceof HTMLSelectElement) {
      const v = shown(value);
      if (![...this.input.options].some((o) => o.value === v)) {
        const o = document.createElement('option');
        o.value = v;
        o.textContent = v;
        this.input.append(o);
      }
      this.input.value = v;
    } else if (this.input) {
      this.input.value = shown(value);
    } else {
      return false;
    }
    this.touched = true;
    this.changed();
    return true;
  }

  /** Shows `message` at the field (null: clears it). */
  error(message: string | null): void {
    this.row.classList.toggle('invalid', message !== null);
    this.message.hidden = message === null;
    this.message.textContent = message ?? '';
  }

  /** This input and those of its rows, by path. */
  all(): FieldInput[] {
    return [this, ...this.subRows.flat().flatMap((i) => i.all())];
  }

  /** Focuses the input. */
  focus(): void {
    (this.input ?? this.boxes[0])?.focus();
  }
}

/** Whether `f` applies to an entry whose words are `word(name)`: given, always
 * required, or required by the words of another field. */
function applies(f: Field, given: boolean, word: (name: string) => string | undefined): 'shown' | 'more' | 'hidden' {
  if (given || f.default.is === 'required') return 'shown';
  if (f.default.is !== 'required-when') return 'more';
  const c = f.default.value;
  const w = word(c.field);
  switch (c.when) {
    case 'is': return w !== undefined && c.words.includes(w) ? 'shown' : 'hidden';
    case 'not': return w === undefined || !c.words.includes(w) ? 'shown' : 'hidden';
    case 'absent': return w === undefined ? 'shown' : 'more';
  }
}

/** One table entry: `[mandrel]`, or one `[[layer]]`. */
class Entry {
  readonly box: HTMLFieldSetElement;
  readonly inputs: FieldInput[];
  private more: HTMLDetailsElement;
  private main: HTMLElement;

  constructor(readonly table: Table, path: string, values: TableValues,
    private changed: () => void, onRemove: (() => void) | null) {
    this.box = document.createElement('fieldset');
    this.box.className = 'entry';
    this.box.dataset.table = path;
    const legend = document.createElement('legend');
    legend.append(document.createElement('span'));
    legend.title = table.help;
    if (onRemove) {
      const remove = document.createElement('button');
      remove.type = 'button';
      remove.className = 'remove';
      remove.textContent = '×';
      remove.title = `Remove this ${table.repeat === 'array' ? 'entry' : 'table'}`;
      remove.addEventListener('click', onRemove);
      legend.append(remove);
    }
    this.main = document.createElement('div');
    this.more = document.createElement('details');
    this.more.className = 'more';
    this.more.append(document.createElement('summary'));
    this.inputs = table.fields.map((f) => new FieldInput(`${path}.${f.name}`, f, values[f.name], () => {
      this.place();
      this.changed();
    }));
    this.box.append(legend, this.main, this.more);
    this.place();
  }

  /** Each field where it applies: shown, under "more", or hidden. */
  place(): void {
    const word = (name: string) => {
      const i = this.inputs.find((x) => x.field.name === name);
      const v = i?.value();
      return v === undefined ? undefined : String(v);
    };
    let more = 0;
    for (const i of this.inputs) {
      const where = applies(i.field, i.present(), word);
      // Moved only when its place changes: a focused input keeps its focus.
      const parent = where === 'more' ? this.more : this.main;
      if (i.row.parentElement !== parent) parent.append(i.row);
      i.row.hidden = where === 'hidden';
      if (where === 'more') more++;
    }
    // In schema order within each part.
    for (const i of this.inputs) i.row.parentElement?.append(i.row);
    const summary = this.more.querySelector('summary');
    if (summary) summary.textContent = `${more} more optional field${more === 1 ? '' : 's'}`;
    this.more.hidden = more === 0;
  }

  /** The entry's values (fields left out absent). */
  values(): TableValues {
    return Object.fromEntries(this.inputs.filter((i) => i.present()).map((i) => [i.field.name, i.value()]));
  }

  /** Shows the field's row (opening "more" when it is there). */
  reveal(i: FieldInput): void {
    i.row.hidden = false;
    if (i.row.parentElement === this.more) this.more.open = true;
  }
}

/** A table's part of the form: its entries and the buttons adding them. */
class TablePart {
  readonly box: HTMLElement;
  entries: Entry[] = [];
  private add: HTMLButtonElement;

  constructor(readonly table: Table, values: TableValues | TableValues[] | undefined, private changed: () => void) {
    this.box = document.createElement('section');
    this.box.className = 'table';
    this.box.dataset.table = table.name;
    this.add = document.createElement('button');
    this.add.type = 'button';
    this.add.className = 'add';
    this.add.textContent = `+ ${table.repeat === 'array' ? `[[${table.name}]]` : `[${table.name}]`}`;
    this.add.title = `Add ${table.repeat === 'array' ? 'an entry of ' : ''}${table.help}`;
    this.add.addEventListener('click', () => {
      this.addEntry({});
      this.changed();
    });
    this.box.append(this.add);
    const list = table.repeat === 'array' ? (Array.isArray(values) ? values : values ? [values] : [])
      : values && !Array.isArray(values) ? [values] : table.required ? [{}] : [];
    for (const v of list) this.addEntry(v);
    this.renumber();
  }

  private addEntry(values: TableValues): void {
    const array = this.table.repeat === 'array';
    const removable = array || !this.table.required;
    let entry: Entry | null = null;
    const path = array ? `${this.table.name}[${this.entries.length}]` : this.table.name;
    entry = new Entry(this.table, path, values, this.changed, removable ? () => {
      if (!entry) return;
      this.entries = this.entries.filter((e) => e !== entry);
      entry.box.remove();
      this.renumber();
      this.changed();
    } : null);
    this.entries.push(entry);
    this.box.insertBefore(entry.box, this.add);
    this.renumber();
  }

  /** Entries' paths and titles by their place (`layer[0]`, "[[layer]] 1"). */
  private renumber(): void {
    const array = this.table.repeat === 'array';
    this.entries.forEach((e, k) => {
      const path = array ? `${this.table.name}[${k}]` : this.table.name;
      const title = e.box.querySelector('legend > span');
      if (title) title.textContent = array ? `[[${this.table.name}]] ${k + 1}` : `[${this.table.name}]`;
      e.box.dataset.table = path;
      for (const i of e.inputs) i.rename(`${path}.${i.field.name}`);
    });
    this.add.hidden = !array && this.entries.length > 0;
  }

  values(): TableValues | TableValues[] | undefined {
    if (this.table.repeat === 'array') return this.entries.length ? this.entries.map((e) => e.values()) : undefined;
    return this.entries[0]?.values();
  }
}

/** The form of one job. */
export class JobForm {
  readonly element: HTMLFormElement;
  private parts: TablePart[];

  /** `changed`: called on every edit; `submit`: Enter in a field. */
  constructor(readonly schema: JobSchema, values: JobValues, changed: () => void, submit: () => void) {
    this.element = document.createElement('form');
    this.element.className = 'job-form';
    this.element.noValidate = true;
    this.parts = schema.tables.map((t) => new TablePart(t, values[t.name], changed));
    this.element.append(...this.parts.map((p) => p.box));
    this.element.addEventListener('submit', (e) => {
      e.preventDefault();
      submit();
    });
    this.element.addEventListener('keydown', (e) => {
      const t = e.target as HTMLElement;
      if (e.key === 'Enter' && (t instanceof HTMLInputElement || t instanceof HTMLSelectElement)) {
        e.preventDefault();
        submit();
      }
    });
  }

  /** The job's values: tables given, fields given. */
  values(): JobValues {
    const out: JobValues = {};
    for (const p of this.parts) {
      const v = p.values();
      if (v !== undefined) out[p.table.name] = v;
    }
    return out;
  }

  /** Every field input by its path (`mandrel.radius`, `layer[1].winding_angle_deg`). */
  private inputs(): Map<string, { input: FieldInput; entry: Entry }> {
    const m = new Map<string, { input: FieldInput; entry: Entry }>();
    for (const p of this.parts) {
      for (const e of p.entries) {
        for (const i of e.inputs.flatMap((x) => x.all())) m.set(i.path, { input: i, entry: e });
      }
    }
    return m;
  }

  /** Every field given, by path: the values the form would send. */
  fields(): Record<string, unknown> {
    const out: Record<string, unknown> = {};
    for (const [path, { input }] of this.inputs()) {
      if (input.field.kind.type !== 'tables' && input.present()) out[path] = input.value();
    }
    return out;
  }

  /** Sets the field at `path` as a user would; false when there is none. */
  set(path: string, value: unknown): boolean {
    const hit = this.inputs().get(path);
    if (!hit) return false;
    hit.entry.reveal(hit.input);
    return hit.input.set(value);
  }

  /**
   * Shows each error at its field; those without one (or naming a field
   * not in the form) are returned, to be shown in the summary.
   */
  showErrors(errors: { field: string | null; message: string }[]): { field: string | null; message: string }[] {
    const inputs = this.inputs();
    for (const { input } of inputs.values()) input.error(null);
    const rest: { field: string | null; message: string }[] = [];
    const at = new Map<string, string[]>();
    for (const e of errors) {
      const hit = e.field ? inputs.get(e.field) : undefined;
      if (!hit || !e.field) {
        rest.push(e);
        continue;
      }
      at.set(e.field, [...(at.get(e.field) ?? []), e.message]);
    }
    let first: FieldInput | null = null;
    for (const [path, messages] of at) {
      const hit = inputs.get(path);
      if (!hit) continue;
      hit.entry.reveal(hit.input);
      hit.input.error(messages.join('\n'));
      first ??= hit.input;
    }
    first?.row.scrollIntoView({ block: 'nearest' });
    return rest;
  }
}
