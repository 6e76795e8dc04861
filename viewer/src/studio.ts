// formcam studio: the job editor. The page `formcam studio` serves asks
// `api/studio` for the folder's jobs, the bundled examples and each kind's
// description, draws the chosen job as a form (form.ts), and through the
// server applies it (checked as the CLI checks it, errors at their field),
// runs it (progress polled from `api/studio/status`, Cancel), resets it to
// the saved file and saves it. The last run's result is `formcam view`'s
// page in an iframe (`runs/<name>/`), left in place when a change is
// refused or a run fails; the runs list (runs.ts) shows any other and
// compares two (compare.ts). `window.formcamStudio` lets tests drive it.
import './studio.css';
import * as api from './api';
import { JobForm } from './form';
import type { JobSchema, JobValues } from './form';
import { RunsList } from './runs';
import type { RunEntry } from './runs';
import { openCompare } from './compare';
import type { CompareState } from './compare';
import { esc } from './view2d';

/** `api/studio`. */
interface StudioBody {
  folder: string;
  job: string | null;
  kinds: { kind: string; schema: JobSchema }[];
  jobs: { file: string; kind: string }[];
  examples: { name: string; kind: string }[];
}

/** `api/studio/job`, and what `api/studio/example` answers. */
interface JobBody { file: string | null; kind: string; text: string; values: JobValues }

/** An error of a job, at its field when it names one (`table.field`, `layer[2].field`). */
interface FieldError { field: string | null; line?: number | null; message: string }

/** `api/studio/status`. */
interface Status {
  run: string | null;
  job: string | null;
  state: 'idle' | 'running' | 'done' | 'failed' | 'cancelled';
  phase: string | null;
  done: number;
  total: number;
  elapsed_s: number;
  line: string | null;
  error: string | null;
}

/** What `window.formcamStudio.state()` returns. */
export interface StudioState {
  /** The job file edited (null before one is chosen). */
  job: string | null;
  kind: string | null;
  /** Every field given in the form, by path (`mandrel.radius`, `layer[1].winding_angle_deg`). */
  fields: Record<string, unknown>;
  /** The errors shown, by field (`""`: those naming no field). */
  errors: Record<string, string>;
  /** The last run started (or shown), its state and progress (0..1). */
  run: string | null;
  runState: Status['state'];
  progress: number;
  /** The run whose result the iframe shows. */
  shown: string | null;
  /** Whether Pause paused the result's animation. */
  paused: boolean;
  /** Whether the job's text (as last applied) equals the saved file. */
  saved: boolean;
  /** The job's text as last applied. */
  text: string;
  /** The runs listed, newest first; those ticked for comparing. */
  runs: string[];
  selected: string[];
  /** The summary line above the form. */
  summary: string;
}

/** What tests drive the studio with. */
export interface StudioApi {
  ready: Promise<void>;
  state(): StudioState;
  /** Sets a field as a user would; false when the form has none by that path. */
  set(field: string, value: unknown): boolean;
  /** Apply: the form checked by the server; true when clean. */
  apply(): Promise<boolean>;
  /** Run: resolves with the run's name once it ended and, when done, its
   * result is shown; null when the job was refused. */
  run(): Promise<string | null>;
  /** Save: true when written. */
  save(): Promise<boolean>;
  /** Reset: the form back to the saved file. */
  reset(): Promise<void>;
  cancel(): Promise<void>;
  /** Pauses the result's animation; again: plays it on. */
  pause(): void;
  /** Opens the job file `file` of the folder, or the bundled example `example:NAME`. */
  open(job: string): Promise<void>;
  /** Compares two runs side by side. */
  compare(a: string, b: string): Promise<CompareState>;
}

declare global {
  interface Window { formcamStudio: StudioApi }
}

/** How often the status is asked for while a run goes, ms. */
const POLL_MS = 200;

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

/** The JSON answer of `r`, or an error naming `url` and what the server said. */
async function answerOf<T>(url: string, r: Response): Promise<T> {
  const text = await r.text();
  let body: unknown = null;
  try {
    body = JSON.parse(text);
  } catch {
    throw new Error(`${url}: ${r.status} ${text.trim()}`);
  }
  const e = (body as { error?: unknown }).error;
  if (!r.ok && typeof e === 'string') throw new Error(e);
  return body as T;
}

async function postJson<T>(url: string, body: unknown): Promise<T> {
  return answerOf<T>(url, await api.post(url, body));
}

/** Mounts the studio in `host`; resolves once the first job is shown. */
async function mount(host: HTMLElement): Promise<void> {
  host.hidden = false;
  host.innerHTML = `
    <header>
      <strong>formcam studio</strong>
      <span class="folder"></span>
      <select class="job" title="The job edited: a job file of the folder, or a bundled example (copied into the folder)"></select>
      <span class="saved"></span>
      <span class="actions">
        <button type="button" class="apply" title="Check the job as formcam would (Enter in a field)">Apply</button>
        <button type="button" class="run" title="Run the job; its result is shown on the right">Run</button>
        <button type="button" class="pause" title="Pause the result's animation">Pause</button>
        <button type="button" class="cancel" title="Stop the run going" disabled>Cancel</button>
        <button type="button" class="reset" title="Back to the saved file">Reset</button>
        <button type="button" class="save" title="Write the job file (the previous one kept as .bak)">Save</button>
      </span>
      <span class="progress"><progress max="1" value="0"></progress><span class="progress-text"></span></span>
    </header>
    <section class="editor">
      <div class="summary" role="status"></div>
      <div class="form-host"></div>
      <details class="text"><summary>TOML</summary><pre></pre></details>
      <section class="runs-host"></section>
    </section>
    <main class="result">
      <iframe class="result-frame" title="The run's result"></iframe>
      <div class="placeholder">No run yet: Run shows the result here.</div>
      <div class="compare-host" hidden>
        <div class="compare-bar"><button type="button" class="back">back to the result</button></div>
        <div class="compare-body"></div>
      </div>
    </main>`;
  const q = <T extends HTMLElement>(sel: string) => host.querySelector(sel) as T;
  const frame = q<HTMLIFrameElement>('.result-frame');
  const placeholder = q('.placeholder');
  const compareHost = q('.compare-host');
  const summaryLine = q('.summary');
  const formHost = q('.form-host');
  const picker = q<HTMLSelectElement>('select.job');
  const bar = q<HTMLProgressElement>('progress');
  const barText = q('.progress-text');
  const cancelButton = q<HTMLButtonElement>('button.cancel');
  const pauseButton = q<HTMLButtonElement>('button.pause');

  let info = await api.json<StudioBody>('/api/studio');
  q('.folder').textContent = info.folder;
  q('.folder').title = `The folder of jobs: ${info.folder}`;
  const schemas = new Map(info.kinds.map((k) => [k.kind, k.schema]));

  // What is edited: the job, its saved text and the text as last applied.
  let job: JobBody | null = null;
  let savedText = '';
  let text = '';
  let form: JobForm | null = null;
  let errors: FieldError[] = [];
  let summary = '';
  // Runs: the last started, its status; the one shown.
  let status: Status = { run: null, job: null, state: 'idle', phase: null, done: 0, total: 0, elapsed_s: 0, line: null, error: null };
  let shown: string | null = null;
  let paused = false;

  const runs = new RunsList(q('.runs-host'), (name) => void showRun(name), (names) => void compare(names[0], names[1]));

  const setSummary = (s: string, kind: 'ok' | 'error' | 'info') => {
    summary = s;
    summaryLine.textContent = s;
    summaryLine.className = `summary ${kind}`;
  };
  const showSaved = () => {
    const saved = q('.saved');
    saved.textContent = job ? (text === savedText ? 'saved' : 'not saved') : '';
    saved.className = `saved ${text === savedText ? 'clean' : 'dirty'}`;
    q('details.text pre').textContent = text;
  };
  /** Shows `errs` at their fields and the rest, and a count, in the summary. */
  const showErrors = (errs: FieldError[]) => {
    errors = errs;
    const rest = form ? form.showErrors(errs) : errs;
    if (errs.length === 0) return;
    const n = errs.length;
    const first = rest[0] ?? errs[0];
    setSummary(`${n} error${n === 1 ? '' : 's'}: ${first.message}${rest.length > 1 ? ` (and ${rest.length - 1} more not at a field)` : ''}`, 'error');
    // Those at no field listed in full under the line.
    if (rest.length > 0) {
      const ul = document.createElement('ul');
      ul.className = 'unplaced';
      ul.innerHTML = rest.map((e) => `<li>${esc(e.message)}</li>`).join('');
      summaryLine.append(ul);
    }
  };

  const fillPicker = () => {
    const opt = (value: string, label: string) => `<option value="${esc(value)}">${esc(label)}</option>`;
    picker.innerHTML = (job?.file ? '' : opt('', '(choose a job)')) +
      `<optgroup label="jobs in the folder">${info.jobs.map((j) => opt(j.file, `${j.file} (${j.kind})`)).join('')}</optgroup>` +
      `<optgroup label="examples (copied into the folder)">${info.examples.map((e) => opt(`example:${e.name}`, `${e.name} (${e.kind})`)).join('')}</optgroup>`;
    picker.value = job?.file ?? '';
  };

  /** Shows `body` as the job edited. */
  const edit = (body: JobBody) => {
    const schema = schemas.get(body.kind);
    if (!schema) throw new Error(`${body.file ?? 'the job'}: no description of the kind ${body.kind}`);
    job = body;
    savedText = body.text;
    text = body.text;
    form = new JobForm(schema, body.values, () => {
      q('.saved').textContent = 'edited';
      q('.saved').className = 'saved dirty';
    }, () => void apply());
    formHost.replaceChildren(form.element);
    errors = [];
    setSummary(`${body.file ?? ''}: ${schema.help}`, 'info');
    fillPicker();
    showSaved();
  };

  const open = async (choice: string) => {
    if (choice.startsWith('example:')) {
      const body = await postJson<JobBody>('/api/studio/example', { name: choice.slice('example:'.length) });
      info = await api.json<StudioBody>('/api/studio');
      edit(body);
    } else if (choice !== '') {
      edit(await api.json<JobBody>(`/api/studio/job?file=${encodeURIComponent(choice)}`));
    }
  };
  picker.addEventListener('change', () => {
    open(picker.value).catch((e) => {
      fillPicker();
      setSummary(String(e instanceof Error ? e.message : e), 'error');
    });
  });

  const body = () => ({ file: job?.file ?? null, kind: job?.kind, text: savedText, values: form?.values() ?? {} });

  /** Apply: the job checked, its new text kept, errors at their fields. */
  const apply = async (): Promise<boolean> => {
    if (!job) return false;
    const r = await postJson<{ ok: boolean; text?: string; errors?: FieldError[] }>('/api/studio/apply', body());
    if (typeof r.text === 'string') text = r.text;
    showSaved();
    form?.showErrors([]);
    errors = [];
    if (!r.ok) {
      showErrors(r.errors ?? []);
      return false;
    }
    setSummary('checked: no errors', 'ok');
    return true;
  };

  const showProgress = (s: Status) => {
    status = s;
    const going = s.state === 'running';
    cancelButton.disabled = !going;
    if (going && s.total > 0) bar.value = Math.min(1, s.done / s.total);
    else if (going) bar.removeAttribute('value');
    else bar.value = s.state === 'done' ? 1 : 0;
    bar.className = s.state;
    const steps = s.total > 0 ? ` ${s.done}/${s.total}` : '';
    barText.textContent = s.run
      ? `${s.state}${s.phase ? ` ${s.phase}` : ''}${steps}, ${s.elapsed_s.toFixed(1)} s`
      : '';
    barText.title = s.line ?? s.error ?? '';
  };

  /** Polls the status until `name` ends (or another run replaced it). */
  const watch = async (name: string): Promise<Status> => {
    for (;;) {
      const s = await api.json<Status>('/api/studio/status');
      if (s.run !== name) return { ...status, run: name, state: 'cancelled' };
      showProgress(s);
      if (s.state === 'done' || s.state === 'failed' || s.state === 'cancelled') return s;
      await sleep(POLL_MS);
    }
  };

  const refreshRuns = async () => {
    runs.update(await api.json<RunEntry[]>('/api/studio/runs'));
  };

  /** Shows run `name`'s result; resolves once its page is ready. */
  const showRun = async (name: string) => {
    compareHost.hidden = true;
    frame.hidden = false;
    placeholder.hidden = true;
    shown = name;
    showPaused(false);
    runs.mark(name);
    const loaded = new Promise<void>((res) => frame.addEventListener('load', () => res(), { once: true }));
    frame.src = `runs/${encodeURIComponent(name)}/`;
    await loaded;
    await (frame.contentWindow as (Window & typeof globalThis) | null)?.formcam?.ready;
  };

  let running: Promise<string | null> | null = null;
  /** Run: applied first (refused with errors at their fields), then run on the server. */
  const run = async (): Promise<string | null> => {
    if (!(await apply())) return null;
    const r = await api.post('/api/studio/run', body());
    const answer = await answerOf<{ run?: string; errors?: FieldError[] }>('/api/studio/run', r);
    if (!answer.run) {
      showErrors(answer.errors ?? []);
      return null;
    }
    const name = answer.run;
    setSummary(`running ${name}`, 'info');
    const end = await watch(name);
    await refreshRuns();
    if (end.state === 'done') {
      setSummary(end.line ?? `${name}: done`, 'ok');
      await showRun(name);
    } else if (end.state === 'failed') {
      setSummary(end.error ?? `${name}: failed`, 'error');
    } else {
      setSummary(`${name}: cancelled`, 'info');
    }
    return name;
  };
  const startRun = () => {
    const p = run();
    running = p;
    void p.finally(() => { if (running === p) running = null; });
    return p;
  };

  const save = async (): Promise<boolean> => {
    if (!job?.file) return false;
    const r = await api.post('/api/studio/save', body());
    const answer = await answerOf<{ ok: boolean; file?: string; text?: string; errors?: FieldError[] }>('/api/studio/save', r);
    form?.showErrors([]);
    errors = [];
    if (!answer.ok) {
      showErrors(answer.errors ?? []);
      return false;
    }
    if (typeof answer.text === 'string') {
      savedText = answer.text;
      text = answer.text;
    }
    setSummary(`saved ${answer.file ?? job.file} (the previous version as ${answer.file ?? job.file}.bak)`, 'ok');
    showSaved();
    return true;
  };

  const reset = async () => {
    if (!job?.file) return;
    await open(job.file);
    setSummary(`${job.file}: as saved`, 'info');
  };

  const cancel = async () => {
    showProgress(await postJson<Status>('/api/studio/cancel', {}));
  };

  /** Pauses the result's animation; pressed again, plays it on. */
  const pause = () => {
    const view = (frame.contentWindow as (Window & typeof globalThis) | null)?.formcam;
    if (!view || frame.hidden) return;
    if (paused) view.play();
    else view.pause();
    showPaused(!paused);
  };
  const showPaused = (p: boolean) => {
    paused = p;
    pauseButton.textContent = p ? 'Resume' : 'Pause';
    pauseButton.title = p ? "Play the result's animation on" : "Pause the result's animation";
  };

  const compare = async (a: string, b: string): Promise<CompareState> => {
    runs.select([a, b]);
    frame.hidden = true;
    placeholder.hidden = true;
    compareHost.hidden = false;
    const target = q('.compare-body');
    return openCompare(target, [a, b].map((name) => ({ name, base: `runs/${encodeURIComponent(name)}/` })));
  };
  q('button.back').addEventListener('click', () => {
    compareHost.hidden = true;
    if (shown) frame.hidden = false;
    else placeholder.hidden = false;
  });

  /** A button's action, its failure shown in the summary. */
  const act = (f: () => Promise<unknown>) => () => {
    f().catch((e) => setSummary(String(e instanceof Error ? e.message : e), 'error'));
  };
  q('button.apply').addEventListener('click', act(apply));
  q('button.run').addEventListener('click', act(startRun));
  q('button.save').addEventListener('click', act(save));
  q('button.reset').addEventListener('click', act(reset));
  cancelButton.addEventListener('click', act(cancel));
  pauseButton.addEventListener('click', pause);

  // The job preselected, else the folder's first; the runs; a run going on.
  fillPicker();
  const first = info.job ?? info.jobs[0]?.file ?? null;
  if (first) await open(first);
  else setSummary('Choose a job of the folder or an example above.', 'info');
  await refreshRuns();
  showProgress(await api.json<Status>('/api/studio/status'));
  if (status.state === 'running' && status.run) {
    const name = status.run;
    void watch(name).then(refreshRuns);
  }
  // The newest result shown: the previous session's work is not hidden.
  const newest = await api.json<RunEntry[]>('/api/studio/runs').then((rs) => rs.find((r) => r.state === 'done'));
  frame.hidden = true;
  if (newest) await showRun(newest.name);

  const ready = window.formcamStudio.ready;
  window.formcamStudio = {
    ready,
    state: () => ({
      job: job?.file ?? null,
      kind: job?.kind ?? null,
      fields: form?.fields() ?? {},
      errors: Object.fromEntries(errors.map((e) => [e.field ?? '', e.message])),
      run: status.run,
      runState: status.state,
      progress: status.total > 0 ? status.done / status.total : status.state === 'done' ? 1 : 0,
      shown,
      paused,
      saved: text === savedText,
      text,
      runs: runs.names(),
      selected: runs.selected(),
      summary,
    }),
    set: (field, value) => form?.set(field, value) ?? false,
    apply,
    run: startRun,
    save,
    reset,
    cancel,
    pause,
    open,
    compare,
  };
}

/** Opens the studio in `host`: `window.formcamStudio` set at once, its
 * `ready` resolved once the first job is shown. */
export function openStudio(host: HTMLElement): Promise<void> {
  const notYet = () => { throw new Error('formcam studio: not ready'); };
  const p = mount(host);
  // Set before `mount` first awaits, replaced by it when done.
  window.formcamStudio = {
    ready: p,
    state: notYet,
    set: notYet,
    apply: notYet,
    run: notYet,
    save: notYet,
    reset: notYet,
    cancel: notYet,
    pause: notYet,
    open: notYet,
    compare: notYet,
  };
  return p;
}
