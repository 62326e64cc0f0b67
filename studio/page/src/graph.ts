// The graph editor: the selected channel's curve over the dope sheet's stretch of time, drawn
// from avar's own engine (WebAssembly), so the line is what the figure will do. The channel's
// range is drawn, and where the curve asks for more than the channel's speed limit the line is
// red. Drag a key to move it in time and value; drag a handle the show gives to reshape it.
import { drawPlayhead, fitCanvas, themeColor, TimeAxis } from './axis';
import { describeFinding } from './findings';
import type { Key } from './protocol';
import { firstKeyAtOrAfter, numericValue } from './protocol';
import { drawWaveform } from './waveform';
import type { StudioState } from './state';

const GUTTER = 120;
const PAD = 14;

type Drag =
  | {
      kind: 'key';
      index: number;
      x: number;
      y: number;
      applied: [number, number];
      busy: boolean;
      started: boolean;
      pending: [number, number] | null;
    }
  | { kind: 'handle'; index: number; side: 'left' | 'right'; busy: boolean; started: boolean; pending: [number, number] | null };

export class GraphEditor {
  private drag: Drag | null = null;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly state: StudioState,
  ) {
    canvas.addEventListener('pointerdown', (e) => this.down(e));
    canvas.addEventListener('pointermove', (e) => this.move(e));
    canvas.addEventListener('pointerup', (e) => {
      this.move(e);
      this.drag = null;
      canvas.releasePointerCapture(e.pointerId);
    });
    new ResizeObserver(() => state.changed()).observe(canvas);
  }

  private axes(): { time: TimeAxis; y: (v: number) => number; v: (y: number) => number } | null {
    const spec = this.state.rig?.channels.find((c) => c.name === this.state.channel);
    if (!spec) return null;
    const time = new TimeAxis(this.state.view.t0, this.state.view.t1, GUTTER, this.canvas.clientWidth - 8);
    const span = spec.max - spec.min || 1;
    const lo = spec.min - 0.08 * span;
    const hi = spec.max + 0.08 * span;
    const h = this.canvas.clientHeight;
    return {
      time,
      y: (v) => PAD + ((hi - v) / (hi - lo)) * (h - 2 * PAD),
      v: (y) => hi - ((y - PAD) / (h - 2 * PAD)) * (hi - lo),
    };
  }

  /// A key's handle on one side as the engine computes it, where a Bezier segment uses it: the
  /// left handle shapes the segment from the previous key, the right one the segment to the next.
  private handle(channel: string, index: number, side: 'left' | 'right'): [number, number] | null {
    const keys = this.state.keys(channel);
    const owner = side === 'left' ? keys[index - 1] : keys[index];
    if (!owner || owner.interpolation !== 'bezier' || (side === 'right' && index + 1 >= keys.length)) return null;
    return this.state.engine.handleOf(channel, index, side);
  }

  private hit(x: number, y: number): Drag | null {
    const a = this.axes();
    const channel = this.state.channel;
    if (!a || !channel) return null;
    const keys = this.state.keys(channel);
    for (const [index, key] of keys.entries()) {
      for (const side of ['left', 'right'] as const) {
        const handle = this.handle(channel, index, side);
        if (handle && Math.hypot(a.time.x(handle[0]) - x, a.y(handle[1]) - y) < 6)
          return { kind: 'handle', index, side, busy: false, started: false, pending: null };
      }
      if (Math.hypot(a.time.x(key.time) - x, a.y(numericValue(key)) - y) < 7)
        return { kind: 'key', index, x, y, applied: [0, 0], busy: false, started: false, pending: null };
    }
    return null;
  }

  private down(e: PointerEvent): void {
    const hit = this.hit(e.offsetX, e.offsetY);
    if (!hit || !this.state.channel) return;
    this.canvas.setPointerCapture(e.pointerId);
    this.drag = hit;
    this.state.selection.clear();
    this.state.selection.set(this.state.channel, new Set([hit.index]));
    this.state.changed();
  }

  private move(e: PointerEvent): void {
    const drag = this.drag;
    const a = this.axes();
    const channel = this.state.channel;
    if (!drag || !a || !channel) return;
    if (drag.kind === 'key') void this.moveKey(drag, channel, a, e.offsetX, e.offsetY);
    else void this.moveHandle(drag, channel, [a.time.t(e.offsetX), a.v(e.offsetY)]);
  }

  /// Moves the key by what the pointer travelled in time and value, one edit in flight at a time
  /// (the newest position is sent when it is answered); the whole drag is one undo step.
  private async moveKey(
    drag: Extract<Drag, { kind: 'key' }>,
    channel: string,
    a: NonNullable<ReturnType<GraphEditor['axes']>>,
    x: number,
    y: number,
  ): Promise<void> {
    drag.pending = [x, y];
    if (drag.busy) return;
    drag.busy = true;
    while (drag.pending) {
      const [px, py] = drag.pending;
      drag.pending = null;
      const dt = (px - drag.x) * a.time.secondsPerPixel() - drag.applied[0];
      const dv = a.v(py) - a.v(drag.y) - drag.applied[1];
      if (Math.abs(dt) < 1e-4 && Math.abs(dv) < 1e-6) continue;
      if (await this.state.edit([{ op: 'move', channel, keys: [drag.index], dt, dv }], drag.started)) {
        drag.applied = [drag.applied[0] + dt, drag.applied[1] + dv];
        drag.started = true;
      }
    }
    drag.busy = false;
  }

  /// Sets the key with the handle where the pointer is (an automatic handle becomes aligned, as
  /// Blender does when one is dragged); the newest position wins when edits queue.
  private async moveHandle(drag: Extract<Drag, { kind: 'handle' }>, channel: string, at: [number, number]): Promise<void> {
    drag.pending = at;
    if (drag.busy) return;
    drag.busy = true;
    while (drag.pending) {
      const point = drag.pending;
      drag.pending = null;
      const key = this.state.keys(channel)[drag.index];
      if (!key) break;
      const typeField = drag.side === 'left' ? 'left_type' : 'right_type';
      // The side's type as the show file defaults it: free where a handle is given.
      const type = key[typeField] ?? (key[drag.side] ? 'free' : 'auto_clamped');
      const changed: Key = { ...key, [drag.side]: point };
      if (type === 'auto' || type === 'auto_clamped' || type === 'vector') changed[typeField] = type === 'vector' ? 'free' : 'aligned';
      if (await this.state.edit([{ op: 'set', channel, key: drag.index, value: changed }], drag.started)) drag.started = true;
    }
    drag.busy = false;
  }

  render(): void {
    const g = fitCanvas(this.canvas);
    const width = this.canvas.clientWidth;
    const height = this.canvas.clientHeight;
    g.clearRect(0, 0, width, height);
    const color = themeColor;
    const a = this.axes();
    const channel = this.state.channel;
    const spec = this.state.rig?.channels.find((c) => c.name === channel);
    g.font = '11px system-ui, sans-serif';
    if (!a || !channel || !spec) {
      g.fillStyle = color('--muted');
      g.fillText('select a channel', GUTTER + 8, 20);
      return;
    }
    g.fillStyle = color('--text');
    g.fillText(`${channel} (${spec.unit})`, 8, 16);
    // The channel's range and rest.
    g.strokeStyle = color('--limit');
    g.setLineDash([5, 4]);
    for (const v of [spec.min, spec.max]) {
      const y = Math.round(a.y(v)) + 0.5;
      g.beginPath();
      g.moveTo(GUTTER, y);
      g.lineTo(width, y);
      g.stroke();
      g.fillStyle = color('--muted');
      g.fillText(`${v} ${spec.unit}`, GUTTER - 60, y + 4);
    }
    g.setLineDash([]);

    // The check's findings on this channel: a band over the span, what it asks and what is allowed.
    // Labels on four lines, each where it does not cover another; the rest are in the dope
    // sheet's tooltips.
    const lineEnds = [0, 0, 0, 0];
    for (const f of this.state.findings) {
      if (f.channel !== channel) continue;
      const xa = Math.max(GUTTER, a.time.x(f.t0));
      const xb = Math.max(xa + 3, a.time.x(f.t1));
      if (xb <= GUTTER || xa >= width) continue;
      g.fillStyle = color('--over-span');
      g.fillRect(xa, 0, xb - xa, height);
      const text = describeFinding(f);
      const x = Math.min(xa + 4, width - 260);
      const line = lineEnds.findIndex((end) => end <= x);
      if (line < 0) continue;
      g.fillStyle = color('--over');
      g.fillText(text, x, 30 + 14 * line);
      lineEnds[line] = x + g.measureText(text).width + 12;
    }

    // The sound the track follows (a jaw's voice), behind the curve.
    const wave = this.state.waveforms.get(channel);
    if (wave) {
      g.globalAlpha = 0.4;
      drawWaveform(g, a.time, wave, GUTTER, width, 0, height);
      g.globalAlpha = 1;
    }
    // The curve, two pixels a sample, from the engine; red where it is faster than allowed.
    const n = Math.max(2, Math.floor((width - GUTTER) / 2));
    const times = new Float64Array(n);
    for (let i = 0; i < n; i++) times[i] = a.time.t(GUTTER + (i * (width - 8 - GUTTER)) / (n - 1));
    const values = this.state.engine.sampleMany(channel, times);
    if (values) {
      // Before the first key and after the last the curve is its extrapolation (held, sloped or
      // cycled): drawn dashed, one path a side so that the dashes run on.
      const keys = this.state.keys(channel);
      const first = keys[0]?.time ?? 0;
      const last = keys[keys.length - 1]?.time ?? 0;
      const extrapolated = (t0: number, t1: number) => t1 <= first || t0 >= last;
      // One path per run of pieces drawn alike.
      let run: boolean | null = null;
      const finish = () => {
        if (run === null) return;
        g.strokeStyle = run ? color('--over') : color('--curve');
        g.lineWidth = run ? 3 : 2;
        g.stroke();
        run = null;
      };
      for (let i = 1; i < n; i++) {
        const t0 = times[i - 1] ?? 0;
        const t1 = times[i] ?? 0;
        if (extrapolated(t0, t1)) {
          finish();
          continue;
        }
        const v0 = values[i - 1] ?? 0;
        const v1 = values[i] ?? 0;
        const over = Math.abs(v1 - v0) / (t1 - t0) > spec.max_velocity || v1 > spec.max || v1 < spec.min;
        if (over !== run) {
          finish();
          run = over;
          g.beginPath();
          g.moveTo(a.time.x(t0), a.y(v0));
        }
        g.lineTo(a.time.x(t1), a.y(v1));
      }
      finish();
      g.strokeStyle = color('--curve');
      g.lineWidth = 2;
      g.setLineDash([5, 4]);
      for (const side of [(t: number) => t <= first, (t: number) => t >= last]) {
        g.beginPath();
        let drawing = false;
        for (let i = 0; i < n; i++) {
          const t = times[i] ?? 0;
          if (!side(t)) continue;
          const x = a.time.x(t);
          const y = a.y(values[i] ?? 0);
          if (drawing) g.lineTo(x, y);
          else g.moveTo(x, y);
          drawing = true;
        }
        g.stroke();
      }
      g.setLineDash([]);
    } else {
      g.fillStyle = color('--muted');
      g.fillText('no track: double-click its row in the dope sheet to add a key', GUTTER + 8, height / 2);
    }
    // Keys and the handles the show gives.
    g.lineWidth = 1;
    const picked = this.state.selection.get(channel);
    // The keys in view (and one beyond each side, whose handles may reach in).
    const keys = this.state.keys(channel);
    const from = Math.max(0, firstKeyAtOrAfter(keys, a.time.t(GUTTER)) - 1);
    const to = Math.min(keys.length, firstKeyAtOrAfter(keys, a.time.t(width)) + 1);
    const dragged = this.state.draggedBy();
    keys.slice(from, to).forEach((key, offset) => {
      const index = from + offset;
      // Keys the dope sheet is dragging are drawn where the pointer has them.
      const ahead = picked?.has(index) ? dragged : 0;
      const kx = a.time.x(key.time + ahead);
      const ky = a.y(numericValue(key));
      for (const side of ['left', 'right'] as const) {
        const handle = this.handle(channel, index, side);
        if (!handle) continue;
        const hx = a.time.x(handle[0] + ahead);
        g.strokeStyle = color('--handle');
        g.beginPath();
        g.moveTo(kx, ky);
        g.lineTo(hx, a.y(handle[1]));
        g.stroke();
        g.fillStyle = color('--handle');
        g.beginPath();
        g.arc(hx, a.y(handle[1]), 3.5, 0, 2 * Math.PI);
        g.fill();
      }
      g.fillStyle = picked?.has(index) ? color('--key-selected') : color('--key');
      g.strokeStyle = color('--key-edge');
      g.beginPath();
      g.arc(kx, ky, 4.5, 0, 2 * Math.PI);
      g.fill();
      g.stroke();
    });
    drawPlayhead(g, a.time, this.state.status?.show_time ?? 0, GUTTER, height);
  }
}
