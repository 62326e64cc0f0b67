// The dope sheet: a ruler with cues, markers (markers.ts) and the playhead, and a row of keys
// per channel. Drag on the ruler to scrub (the figure glides after the playhead); click a key to
// select it (Shift adds), drag a box to select many, drag selected keys to move them in time,
// double-click a row to add a key there with the curve's value, Delete removes the selection.
// Wheel zooms, Shift+wheel pans.
import { drawPlayhead, fitCanvas, formatTime, themeColor, TimeAxis, tickStep, zoomView } from './axis';
import { typingIn } from './dom';
import { Markers } from './markers';
import { drawWaveform } from './waveform';
import { describeFinding } from './findings';
import type { Finding, Key, Layer } from './protocol';
import { firstKeyAtOrAfter, trackKeys } from './protocol';
import type { StudioState } from './state';

const GUTTER = 120;
const RULER = 24;
const ROW = 22;
const KEY_RADIUS = 5;

type Drag =
  | { kind: 'scrub' }
  | {
      kind: 'keys';
      startX: number;
      x: number;
      applied: number;
      /// The moves being sent, one answered before the next; null when none is.
      sending: Promise<void> | null;
      started: boolean;
      pendingX: number | null;
    }
  | { kind: 'box'; x0: number; y0: number; x1: number; y1: number };

export class DopeSheet {
  private drag: Drag | null = null;
  /// A drag of keys let go whose last move is still on its way.
  private landing: Extract<Drag, { kind: 'keys' }> | null = null;
  private lastScrub = 0;
  readonly markers: Markers;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly state: StudioState,
  ) {
    canvas.addEventListener('pointerdown', (e) => this.down(e));
    canvas.addEventListener('pointermove', (e) => this.move(e));
    canvas.addEventListener('pointerup', (e) => this.up(e));
    this.markers = new Markers(state);
    canvas.addEventListener('dblclick', (e) => void this.doubleClick(e));
    canvas.addEventListener('wheel', (e) => this.wheel(e), { passive: false });
    window.addEventListener('keydown', (e) => {
      if (typingIn(e) || (e.target instanceof HTMLInputElement && e.target.type === 'range')) return;
      if (e.key === 'Delete' || e.key === 'Backspace') void this.deleteSelection();
      else if (e.key === 'Home') this.viewWholeShow();
      else if ((e.key === 'ArrowLeft' || e.key === 'ArrowRight') && !e.ctrlKey && !e.metaKey) void this.nudge(e);
      else return;
      e.preventDefault();
    });
    new ResizeObserver(() => state.changed()).observe(canvas);
    state.draggedBy = () => this.ghost();
  }

  axis(): TimeAxis {
    return new TimeAxis(this.state.view.t0, this.state.view.t1, GUTTER, this.canvas.clientWidth - 8);
  }

  private channelAt(y: number): string | null {
    const row = Math.floor((y - RULER) / ROW);
    return y < RULER ? null : (this.state.rig?.channels[row]?.name ?? null);
  }

  private keyAt(x: number, y: number): { channel: string; index: number } | null {
    const channel = this.channelAt(y);
    if (!channel) return null;
    const axis = this.axis();
    const keys = this.state.keys(channel);
    let best: { channel: string; index: number } | null = null;
    let bestDistance = KEY_RADIUS + 3;
    keys.forEach((key, index) => {
      const d = Math.abs(axis.x(key.time) - x);
      if (d <= bestDistance) {
        best = { channel, index };
        bestDistance = d;
      }
    });
    return best;
  }

  /// What the check found under the pointer ("" where nothing), for the tooltip.
  private findingAt(x: number, y: number): string {
    const channel = this.channelAt(y);
    const t = this.axis().t(x);
    const slack = 4 * this.axis().secondsPerPixel();
    return this.state.findings
      .filter((f) => f.channel === channel && t >= f.t0 - slack && t <= f.t1 + slack)
      .map((f) => describeFinding(f))
      .join('\n');
  }

  private scrubTo(x: number): void {
    const t = Math.min(this.state.duration(), Math.max(0, this.axis().t(x)));
    this.state.connection.send({ type: 'scrub', time: t });
    this.lastScrub = t;
    if (this.state.status) this.state.status = { ...this.state.status, show_time: t, paused: true };
    this.state.changed();
  }

  private down(e: PointerEvent): void {
    const { offsetX: x, offsetY: y } = e;
    this.canvas.setPointerCapture(e.pointerId);
    if (y < RULER && x >= GUTTER) {
      this.drag = { kind: 'scrub' };
      this.scrubTo(x);
      return;
    }
    const channel = this.channelAt(y);
    if (channel) this.state.channel = channel;
    const hit = this.keyAt(x, y);
    const selection = this.state.selection;
    if (hit) {
      const picked = selection.get(hit.channel)?.has(hit.index) ?? false;
      if (e.shiftKey) {
        const set = selection.get(hit.channel) ?? new Set<number>();
        if (picked) set.delete(hit.index);
        else set.add(hit.index);
        selection.set(hit.channel, set);
      } else if (!picked) {
        selection.clear();
        selection.set(hit.channel, new Set([hit.index]));
      }
      this.drag = { kind: 'keys', startX: x, x, applied: 0, sending: null, started: false, pendingX: null };
      this.state.setDragging(true);
    } else {
      if (!e.shiftKey) selection.clear();
      this.drag = { kind: 'box', x0: x, y0: y, x1: x, y1: y };
    }
    this.state.changed();
  }

  private move(e: PointerEvent): void {
    const drag = this.drag;
    if (!drag) {
      this.canvas.title = this.findingAt(e.offsetX, e.offsetY);
      return;
    }
    const { offsetX: x, offsetY: y } = e;
    if (drag.kind === 'scrub') {
      this.scrubTo(x);
    } else if (drag.kind === 'box') {
      drag.x1 = x;
      drag.y1 = y;
      this.state.changed();
    } else {
      drag.x = x;
      this.state.changed();
      void this.moveKeys(drag, x);
    }
  }

  /// Seconds the selected keys are drawn ahead of where the studio has them: the pointer's travel
  /// that no answered move has applied yet. The keys follow the pointer at every frame however
  /// long the studio takes over a move of many keys.
  private ghost(): number {
    const drag = this.drag ?? this.landing;
    if (drag?.kind !== 'keys') return 0;
    const wanted = (drag.x - drag.startX) * this.axis().secondsPerPixel();
    return Math.abs(wanted - drag.applied) < 1e-4 ? 0 : wanted - drag.applied;
  }

  /// Moves the selection by what the pointer travelled, one edit in flight at a time (the newest
  /// pointer position is sent when it is answered); a whole drag is one undo step. A refused move
  /// (a key would pass its neighbour) leaves the keys where they were.
  private moveKeys(drag: Extract<Drag, { kind: 'keys' }>, x: number): Promise<void> {
    drag.pendingX = x;
    drag.sending ??= this.sendMoves(drag).finally(() => {
      drag.sending = null;
    });
    return drag.sending;
  }

  private async sendMoves(drag: Extract<Drag, { kind: 'keys' }>): Promise<void> {
    while (drag.pendingX !== null) {
      const wanted = (drag.pendingX - drag.startX) * this.axis().secondsPerPixel();
      drag.pendingX = null;
      const dt = wanted - drag.applied;
      if (Math.abs(dt) < 1e-4) continue;
      const edits = [...this.state.selection].map(([channel, keys]) => ({
        op: 'move' as const,
        channel,
        keys: [...keys].sort((a, b) => a - b),
        dt,
        dv: 0,
      }));
      if (edits.length === 0) break;
      if (await this.state.edit(edits, drag.started)) {
        drag.applied += dt;
        drag.started = true;
      }
    }
  }

  private up(e: PointerEvent): void {
    const drag = this.drag;
    this.drag = null;
    this.canvas.releasePointerCapture(e.pointerId);
    if (drag?.kind === 'box') {
      const axis = this.axis();
      const [xa, xb] = [Math.min(drag.x0, drag.x1), Math.max(drag.x0, drag.x1)];
      const [ya, yb] = [Math.min(drag.y0, drag.y1), Math.max(drag.y0, drag.y1)];
      this.state.rig?.channels.forEach((channel, row) => {
        const cy = RULER + row * ROW + ROW / 2;
        if (cy < ya || cy > yb) return;
        this.state.keys(channel.name).forEach((key, index) => {
          const kx = axis.x(key.time);
          if (kx < xa || kx > xb) return;
          const set = this.state.selection.get(channel.name) ?? new Set<number>();
          set.add(index);
          this.state.selection.set(channel.name, set);
        });
      });
    } else if (drag?.kind === 'keys') {
      // Let the last pointer position land; the keys are drawn where it left them meanwhile.
      drag.x = e.offsetX;
      this.landing = drag;
      void this.moveKeys(drag, e.offsetX).then(() => {
        if (this.landing === drag) this.landing = null;
        this.state.setDragging(false);
        this.state.changed();
      });
    }
    this.state.changed();
  }

  /// On the ruler, a marker is renamed; in a row, a key is added.
  private async doubleClick(e: MouseEvent): Promise<void> {
    if (e.offsetY < RULER) {
      const marker = this.markers.at(this.axis(), e.offsetX);
      if (marker >= 0) await this.markers.rename(marker);
      return;
    }
    await this.addKey(e);
  }

  private async addKey(e: MouseEvent): Promise<void> {
    const channel = this.channelAt(e.offsetY);
    if (!channel || e.offsetX < GUTTER) return;
    const t = Math.max(0, this.axis().t(e.offsetX));
    const spec = this.state.rig?.channels.find((c) => c.name === channel);
    const value = this.state.engine.sample(channel, t) ?? spec?.rest ?? 0;
    const time = Math.round(t * 1000) / 1000;
    const keys = this.state.keys(channel);
    const interpolation = keys.length > 0 ? (keys[0]?.interpolation ?? 'bezier') : 'bezier';
    await this.state.edit([{ op: 'add', channel, keys: [{ time, value, interpolation }] }]);
  }

  /// The whole show in view, with a margin (Home).
  viewWholeShow(): void {
    const d = Math.max(0.01, this.state.duration());
    this.state.view = { t0: -0.02 * d, t1: 1.03 * d };
    this.state.changed();
  }

  /// Moves the selected keys one tick of the rig (Shift: ten) earlier or later: one edit.
  private async nudge(e: KeyboardEvent): Promise<void> {
    const tick = 1 / (this.state.rig?.rate_hz ?? 50);
    const dt = (e.key === 'ArrowLeft' ? -tick : tick) * (e.shiftKey ? 10 : 1);
    const edits = [...this.state.selection]
      .filter(([, keys]) => keys.size > 0)
      .map(([channel, keys]) => ({ op: 'move' as const, channel, keys: [...keys].sort((a, b) => a - b), dt, dv: 0 }));
    if (edits.length > 0) await this.state.edit(edits);
  }

  private async deleteSelection(): Promise<void> {
    const edits = [...this.state.selection]
      .filter(([, keys]) => keys.size > 0)
      .map(([channel, keys]) => ({ op: 'delete' as const, channel, keys: [...keys].sort((a, b) => a - b) }));
    if (edits.length === 0) return;
    this.state.selection.clear();
    await this.state.edit(edits);
  }

  private wheel(e: WheelEvent): void {
    e.preventDefault();
    const axis = this.axis();
    const view = this.state.view;
    if (e.shiftKey || Math.abs(e.deltaX) > Math.abs(e.deltaY)) {
      const dt = (e.shiftKey ? e.deltaY : e.deltaX) * axis.secondsPerPixel();
      view.t0 += dt;
      view.t1 += dt;
    } else {
      zoomView(view, axis.t(Math.max(GUTTER, e.offsetX)), Math.exp(e.deltaY * 0.002));
    }
    this.state.changed();
  }

  /// Rows under the channels, drawn but not edited here: each layer's clip placements, and each
  /// inverse-kinematics target's x, y and z keys (edit those in the show file).
  private extraRows(): ({ kind: 'layer'; layer: Layer } | { kind: 'target'; name: string; axis: 'x' | 'y' | 'z'; keys: Key[] })[] {
    const show = this.state.show?.show;
    const rows: ReturnType<DopeSheet['extraRows']> = [];
    for (const layer of show?.layers ?? []) rows.push({ kind: 'layer', layer });
    for (const [name, target] of Object.entries(show?.targets ?? {}))
      for (const axis of ['x', 'y', 'z'] as const) {
        const keys = trackKeys(target[axis]);
        if (keys.length > 0) rows.push({ kind: 'target', name, axis, keys });
      }
    return rows;
  }

  private drawExtraRows(
    g: CanvasRenderingContext2D,
    axis: TimeAxis,
    rows: ReturnType<DopeSheet['extraRows']>,
    top: number,
    width: number,
  ): void {
    rows.forEach((row, i) => {
      const y = top + i * ROW;
      const cy = y + ROW / 2;
      g.fillStyle = i % 2 ? themeColor('--row-odd') : themeColor('--row-even');
      g.fillRect(0, y, width, ROW);
      g.fillStyle = themeColor('--muted');
      if (row.kind === 'layer') {
        g.fillText(`layer ${row.layer.name}`, 8, cy + 4);
        for (const p of row.layer.clips) {
          // A placement as a bar, its fades as slopes.
          const xa = axis.x(p.start);
          const xb = axis.x(p.end);
          if (xb < GUTTER || xa > width) continue;
          const fadeIn = axis.x(p.start + p.fade_in) - xa;
          const fadeOut = xb - axis.x(p.end - p.fade_out);
          g.fillStyle = themeColor('--clip');
          g.beginPath();
          g.moveTo(Math.max(GUTTER, xa), y + ROW - 3);
          g.lineTo(Math.max(GUTTER, xa + fadeIn), y + 3);
          g.lineTo(Math.max(GUTTER, xb - fadeOut), y + 3);
          g.lineTo(Math.max(GUTTER, xb), y + ROW - 3);
          g.closePath();
          g.fill();
          g.fillStyle = themeColor('--text');
          g.fillText(p.clip, Math.max(GUTTER, xa) + 4, cy + 4);
        }
      } else {
        g.fillText(`target ${row.name}.${row.axis}`, 8, cy + 4);
        g.fillStyle = themeColor('--target-key');
        for (const key of row.keys) {
          const x = axis.x(key.time);
          if (x < GUTTER - KEY_RADIUS || x > width + KEY_RADIUS) continue;
          g.beginPath();
          g.arc(x, cy, KEY_RADIUS - 1, 0, 2 * Math.PI);
          g.fill();
        }
      }
    });
  }

  /// A row's keys as diamonds: only those in view (found by bisection: keys are in time order),
  /// each colour one path, the selected ones moved by the drag's ghost; keys too dense to tell
  /// apart as bars.
  private drawKeys(g: CanvasRenderingContext2D, axis: TimeAxis, keys: Key[], picked: Set<number> | undefined, cy: number, width: number): void {
    const diamond = (x: number) => {
      g.moveTo(x, cy - KEY_RADIUS);
      g.lineTo(x + KEY_RADIUS, cy);
      g.lineTo(x, cy + KEY_RADIUS);
      g.lineTo(x - KEY_RADIUS, cy);
      g.closePath();
    };
    const paint = (fill: string) => {
      g.fillStyle = fill;
      g.strokeStyle = themeColor('--key-edge');
      g.fill();
      g.stroke();
    };
    const first = firstKeyAtOrAfter(keys, axis.t(GUTTER - KEY_RADIUS));
    const last = firstKeyAtOrAfter(keys, axis.t(width + KEY_RADIUS));
    if (last - first > (width - GUTTER) / KEY_RADIUS) {
      // Keys closer than a diamond's half-width on average: a bar over each run of keys less
      // than that apart (a canvas fills one bar far faster than thousands of overlapping paths).
      g.fillStyle = themeColor('--key');
      let runStart = Number.NaN;
      let runEnd = Number.NaN;
      const bar = () => {
        if (!Number.isNaN(runStart)) g.fillRect(runStart - 2, cy - KEY_RADIUS + 1, runEnd - runStart + 4, 2 * KEY_RADIUS - 2);
      };
      for (let index = first; index < last; index++) {
        const x = Math.round(axis.x(keys[index]!.time));
        if (x - runEnd <= KEY_RADIUS) {
          runEnd = x;
          continue;
        }
        bar();
        runStart = runEnd = x;
      }
      bar();
    } else {
      g.beginPath();
      for (let index = first; index < last; index++) if (!picked?.has(index)) diamond(axis.x(keys[index]!.time));
      paint(themeColor('--key'));
    }
    if (!picked || picked.size === 0) return;
    const ghost = this.ghost();
    g.beginPath();
    for (const index of picked) {
      const key = keys[index];
      if (!key) continue;
      const x = axis.x(key.time + ghost);
      if (x >= GUTTER - KEY_RADIUS && x <= width + KEY_RADIUS) diamond(x);
    }
    paint(themeColor('--key-selected'));
  }

  render(): void {
    const rig = this.state.rig;
    const extra = this.extraRows();
    const rows = (rig?.channels.length ?? 0) + extra.length;
    this.canvas.style.height = `${RULER + rows * ROW + 4}px`;
    const g = fitCanvas(this.canvas);
    const width = this.canvas.clientWidth;
    const height = this.canvas.clientHeight;
    const axis = this.axis();
    const color = themeColor;
    g.clearRect(0, 0, width, height);
    g.font = '11px system-ui, sans-serif';

    // Ruler and grid.
    const step = tickStep(70 * axis.secondsPerPixel());
    g.fillStyle = color('--panel');
    g.fillRect(0, 0, width, RULER);
    g.strokeStyle = color('--grid');
    g.fillStyle = color('--muted');
    g.lineWidth = 1;
    for (let t = Math.ceil(this.state.view.t0 / step) * step; t <= this.state.view.t1; t += step) {
      const x = Math.round(axis.x(t)) + 0.5;
      if (x < GUTTER) continue;
      g.beginPath();
      g.moveTo(x, RULER - 6);
      g.lineTo(x, height);
      g.stroke();
      g.fillText(formatTime(t, step), x + 3, 12);
    }
    // The show's end, and time outside it, shaded.
    const end = axis.x(this.state.duration());
    g.fillStyle = color('--outside');
    if (end < width) g.fillRect(Math.max(GUTTER, end), RULER, width - Math.max(GUTTER, end), height - RULER);
    const start = axis.x(0);
    if (start > GUTTER) g.fillRect(GUTTER, RULER, start - GUTTER, height - RULER);
    // Cues on the ruler.
    g.fillStyle = color('--cue');
    for (const cue of this.state.show?.show.cues ?? []) {
      const x = axis.x(cue.time);
      if (x < GUTTER) continue;
      g.beginPath();
      g.moveTo(x - 4, RULER - 8);
      g.lineTo(x + 4, RULER - 8);
      g.lineTo(x, RULER - 2);
      g.fill();
    }

    // Markers: a flag and the name on the ruler (a faint line down the rows comes last).
    g.fillStyle = color('--marker');
    for (const marker of this.markers.list()) {
      const x = axis.x(marker.time);
      if (x < GUTTER || x > width) continue;
      g.fillRect(x, RULER - 12, 2, 12);
      g.fillText(marker.name, x + 4, RULER - 3);
    }

    // Rows: name, keys, selection.
    const findings = new Map<string, Finding[]>();
    for (const f of this.state.findings) findings.set(f.channel, [...(findings.get(f.channel) ?? []), f]);
    rig?.channels.forEach((channel, row) => {
      const y = RULER + row * ROW;
      const cy = y + ROW / 2;
      const selectedRow = this.state.channel === channel.name;
      g.fillStyle = selectedRow ? color('--row-selected') : row % 2 ? color('--row-odd') : color('--row-even');
      g.fillRect(0, y, width, ROW);
      g.fillStyle = color('--text');
      g.fillText(channel.name, 8, cy + 4);
      const keys = this.state.keys(channel.name);
      const picked = this.state.selection.get(channel.name);
      // Spans that ask more than the channel allows, under everything else of the row.
      g.fillStyle = color('--over-span');
      for (const f of findings.get(channel.name) ?? []) {
        const xa = Math.max(GUTTER, axis.x(f.t0));
        const xb = Math.max(xa + 3, axis.x(f.t1));
        if (xb > GUTTER) g.fillRect(xa, y + 2, xb - xa, ROW - 4);
      }
      // The sound the track follows (a jaw's voice), under its keys.
      const wave = this.state.waveforms.get(channel.name);
      if (wave) drawWaveform(g, axis, wave, GUTTER, width, y + 1, ROW - 2);
      // A bar under the keys shows the track's span.
      if (keys.length > 1) {
        const first = keys[0];
        const last = keys[keys.length - 1];
        if (first && last) {
          g.fillStyle = color('--track');
          const xa = Math.max(GUTTER, axis.x(first.time));
          const xb = axis.x(last.time);
          if (xb > xa) g.fillRect(xa, cy - 2, xb - xa, 4);
        }
      }
      this.drawKeys(g, axis, keys, picked, cy, width);
    });
    this.drawExtraRows(g, axis, extra, RULER + (rig?.channels.length ?? 0) * ROW, width);
    g.fillStyle = color('--grid');
    g.fillRect(GUTTER - 1, 0, 1, height);

    if (this.drag?.kind === 'box') {
      const d = this.drag;
      g.strokeStyle = color('--key-selected');
      g.setLineDash([4, 3]);
      g.strokeRect(Math.min(d.x0, d.x1), Math.min(d.y0, d.y1), Math.abs(d.x1 - d.x0), Math.abs(d.y1 - d.y0));
      g.setLineDash([]);
    }

    g.strokeStyle = color('--marker');
    g.globalAlpha = 0.4;
    for (const marker of this.markers.list()) {
      const x = axis.x(marker.time);
      if (x < GUTTER || x > width) continue;
      g.beginPath();
      g.moveTo(x + 0.5, RULER);
      g.lineTo(x + 0.5, height);
      g.stroke();
    }
    g.globalAlpha = 1;

    // The playhead: where the pointer scrubs to, or where show time is.
    const t = this.drag?.kind === 'scrub' ? this.lastScrub : (this.state.status?.show_time ?? 0);
    drawPlayhead(g, axis, t, GUTTER, height);
  }
}
