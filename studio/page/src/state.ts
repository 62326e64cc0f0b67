// What the page knows: the rig, the show as the server last sent it, the newest status, what is
// selected and which stretch of show time the timeline and graph editor show. Views read it and
// ask for a redraw; only messages from the server change the show.
import type { Connection } from './connection';
import type { CurveEngine } from './engine';
import type { Edit, Finding, Hello, Key, KeysChange, Rig, ShowState, Status, Vocabulary, WaveformTrack } from './protocol';
import { trackKeys } from './protocol';

/// Tracks asked for in one `curves` request when no view is waiting for them.
const CURVES_PER_REQUEST = 8;

/// Keys picked, per channel (indices into the channel's track, in time order).
export type Selection = Map<string, Set<number>>;

export class StudioState {
  rig: Rig | null = null;
  vocabulary: Vocabulary = { interpolations: [], easings: [], handle_types: [], extrapolations: [] };
  /// What the show asks beyond the rig's limits, as the studio's check found it.
  findings: Finding[] = [];
  /// The sound each track made from audio follows (a jaw's voice), by channel.
  waveforms: Map<string, WaveformTrack> = new Map();
  /// Keys copied (Ctrl+C), per channel, their times from the earliest copied key.
  clipboard: Map<string, Key[]> = new Map();
  show: ShowState | null = null;
  status: Status | null = null;
  /// The channel the graph editor and the pose panel point at.
  channel: string | null = null;
  selection: Selection = new Map();
  /// Seconds ahead of where the studio has them that the selected keys are drawn while a drag
  /// moves them (the dope sheet's pointer travel not answered yet); 0 without a drag.
  draggedBy: () => number = () => 0;
  /// The visible stretch of show time, seconds.
  view = { t0: 0, t1: 10 };
  /// The last refusal or problem (or, `noticeIsProblem` false, news such as a save), shown in the
  /// status bar.
  notice = '';
  noticeIsProblem = true;
  private listeners: (() => void)[] = [];
  private scheduled = false;

  constructor(
    readonly connection: Connection,
    readonly engine: CurveEngine,
  ) {}

  onChange(listener: () => void): void {
    this.listeners.push(listener);
  }

  /// Redraws at the next animation frame, once however often it is asked.
  changed(): void {
    if (this.scheduled) return;
    this.scheduled = true;
    requestAnimationFrame(() => {
      this.scheduled = false;
      for (const listener of this.listeners) listener();
    });
  }

  takeHello(hello: Hello): void {
    const first = this.rig === null;
    this.rig = hello.rig;
    this.vocabulary = hello.vocabulary;
    this.takeShow(hello);
    if (first) {
      // The whole show, with a margin so the first and last keys are not cut.
      const d = Math.max(1, hello.show.duration);
      this.view = { t0: -0.02 * d, t1: 1.03 * d };
      this.channel = hello.rig.channels[0]?.name ?? null;
    }
    this.refreshWaveforms();
  }

  /// The voices of tracks made from sound files, where each starts now.
  private refreshWaveforms(): void {
    void this.connection.request({ type: 'waveform' })?.then((reply) => {
      if (reply?.type !== 'waveform') return;
      this.waveforms = new Map(reply.tracks.map((w) => [w.channel, w]));
      this.changed();
    });
  }

  takeShow(show: ShowState): void {
    const keysBefore = this.show ? this.keyCounts() : null;
    this.show = show;
    // A selection survives an edit that kept every track's key count (a move, a set); otherwise
    // indices may name other keys, so it is dropped.
    if (keysBefore) this.keepSelection(keysBefore);
    const channels = new Set(Object.keys(show.show.tracks));
    this.engine.keepOnly(channels);
    for (const channel of channels) this.staleCurves.add(channel);
    this.refreshCurves();
    this.requestCheck();
    // A time edit moves where a track's sound starts (and undo moves it back).
    if (keysBefore && this.waveforms.size > 0) this.refreshWaveforms();
    this.changed();
  }

  /// An edit, undo or redo of existing tracks' keys: the stretches of keys that changed.
  takeKeys(change: KeysChange): void {
    const show = this.show;
    if (!show) return;
    const keysBefore = this.keyCounts();
    for (const splice of change.tracks) {
      const track = show.show.tracks[splice.channel];
      if (!track) continue;
      trackKeys(track).splice(splice.from, splice.remove, ...splice.keys);
      this.staleCurves.add(splice.channel);
    }
    this.show = { ...show, version: change.version, file: change.file, modified: change.modified, undo: change.undo, redo: change.redo };
    this.keepSelection(keysBefore);
    this.refreshCurves();
    this.requestCheck();
    this.changed();
  }

  private keepSelection(keysBefore: Map<string, number>): void {
    const after = this.keyCounts();
    for (const channel of this.selection.keys()) if (keysBefore.get(channel) !== after.get(channel)) this.selection.delete(channel);
  }

  /// Whether a pointer is dragging keys or handles: what can wait for its end waits (the other
  /// tracks' curves, the check), so that the drag's frames and the studio's answers stay quick.
  private dragging = false;
  private dragEnded: (() => void)[] = [];

  setDragging(on: boolean): void {
    this.dragging = on;
    if (!on) for (const resume of this.dragEnded.splice(0)) resume();
  }

  /// Resolves when no drag is under way and every message in flight is answered.
  private async settled(): Promise<void> {
    for (;;) {
      if (this.dragging) await new Promise<void>((resume) => this.dragEnded.push(resume));
      await this.connection.whenIdle();
      if (!this.dragging) return;
    }
  }

  /// Channels whose keys changed since the engine last had their curves.
  private staleCurves = new Set<string>();
  private curvesInFlight = false;
  private curvesWaiting = false;

  /// Brings the engine's curves up to date, one request at a time: the graph editor's channel at
  /// once, the others once every message in flight is answered (during a drag, when it ends), so
  /// a drag of keys on many tracks costs the page one track's curve per answer.
  private refreshCurves(): void {
    if (this.curvesInFlight || this.staleCurves.size === 0) return;
    const first = this.channel !== null && this.staleCurves.has(this.channel) ? [this.channel] : null;
    if (first) {
      this.fetchCurves(first);
      return;
    }
    if (this.curvesWaiting) return;
    this.curvesWaiting = true;
    void this.settled().then(() => {
      this.curvesWaiting = false;
      // A few tracks a request: a long show's curves arrive in pieces the page takes between
      // frames, not in one message that stops it for seconds.
      if (!this.curvesInFlight && this.staleCurves.size > 0) this.fetchCurves([...this.staleCurves].slice(0, CURVES_PER_REQUEST));
    });
  }

  private fetchCurves(channels: string[]): void {
    for (const channel of channels) this.staleCurves.delete(channel);
    const request = this.connection.request({ type: 'curves', channels });
    if (!request) {
      for (const channel of channels) this.staleCurves.add(channel);
      return;
    }
    this.curvesInFlight = true;
    void request.then((reply) => {
      this.curvesInFlight = false;
      if (reply?.type === 'curves') {
        const problems = this.engine.putTracks(reply.tracks);
        if (problems.length > 0) this.notice = `the page's engine refused: ${problems.join('; ')}`;
      }
      this.changed();
      this.refreshCurves();
    });
  }

  /// Asks for the feasibility check of the newest show once every message in flight is answered
  /// (a drag sends a move per pointer event; the check of its last position is the one that
  /// matters), once however many shows arrive meanwhile.
  private checkWanted = false;
  private requestCheck(): void {
    if (this.checkWanted) return;
    this.checkWanted = true;
    void this.settled().then(async () => {
      this.checkWanted = false;
      const reply = await this.connection.request({ type: 'check' });
      if (reply?.type !== 'check') return;
      this.findings = reply.findings;
      this.changed();
    });
  }

  keys(channel: string) {
    return trackKeys(this.show?.show.tracks[channel]);
  }

  duration(): number {
    return this.show?.show.duration ?? 10;
  }

  /// Sends edits as one undo step (`continues`: the next move of a drag); the reply's refusal
  /// becomes the notice. Resolves true when the studio took them.
  async edit(edits: Edit[], continues = false): Promise<boolean> {
    const reply = await this.connection.request({ type: 'edit', edits, ...(continues ? { continues: true } : {}) });
    return this.answer(reply);
  }

  /// Sends a message that is answered `ok` or `error`; the error becomes the notice.
  async ask(message: object): Promise<boolean> {
    return this.answer(await this.connection.request(message));
  }

  private answer(reply: Awaited<ReturnType<Connection['request']>>): boolean {
    this.noticeIsProblem = true;
    if (reply === null || reply === undefined) {
      this.notice = 'not connected to the studio';
    } else if (reply.type === 'error') {
      this.notice = reply.message;
    } else {
      this.notice = '';
    }
    this.changed();
    return reply !== null && reply !== undefined && reply.type !== 'error';
  }

  private keyCounts(): Map<string, number> {
    const counts = new Map<string, number>();
    for (const [channel, track] of Object.entries(this.show?.show.tracks ?? {})) counts.set(channel, trackKeys(track).length);
    return counts;
  }
}
