// avar's curve engine compiled to WebAssembly (avar_curves.js, loaded by index.html): the page
// builds every track from the server's flat keys (the `curves` message) and samples it exactly
// as the figure does, bit for bit. No curve maths lives in TypeScript.

interface CurveModule {
  _avar_curve_build(flat: number, count: number): number;
  _avar_curve_rebuild(id: number, flat: number, count: number): number;
  _avar_curve_free(id: number): void;
  _avar_curve_sample(id: number, t: number): number;
  _avar_curve_sample_many(id: number, times: number, out: number, count: number): void;
  _avar_curve_handles(flat: number, count: number, out: number): number;
  _avar_error(): number;
  _malloc(bytes: number): number;
  _free(address: number): void;
  UTF8ToString(address: number): string;
  HEAPF64: Float64Array;
}

declare global {
  interface Window {
    AvarCurves?: () => Promise<CurveModule>;
  }
}

export class CurveEngine {
  private curves = new Map<string, number>();
  private flats = new Map<string, number[]>();
  private handleCache = new Map<string, Float64Array>();
  private constructor(private readonly module: CurveModule) {}

  static async load(): Promise<CurveEngine> {
    if (!window.AvarCurves) throw new Error('the curve engine (avar_curves.js) did not load');
    return new CurveEngine(await window.AvarCurves());
  }

  /// Takes the tracks of a `curves` message: a channel the engine has is rebuilt from its new keys
  /// (reusing the segments they left alone), another is built. Returns the channels whose keys the
  /// engine refused, with its reason (the server built them, so this is not expected).
  putTracks(tracks: Record<string, number[]>): string[] {
    const problems: string[] = [];
    for (const [channel, flat] of Object.entries(tracks)) {
      this.handleCache.delete(channel);
      this.flats.set(channel, flat);
      const address = this.toHeap(flat);
      const old = this.curves.get(channel);
      if (old !== undefined && this.module._avar_curve_rebuild(old, address, flat.length) === 0) {
        this.module._free(address);
        continue;
      }
      if (old !== undefined) this.module._avar_curve_free(old);
      const id = this.module._avar_curve_build(address, flat.length);
      this.module._free(address);
      if (id < 0) {
        problems.push(`${channel}: ${this.module.UTF8ToString(this.module._avar_error())}`);
        this.curves.delete(channel);
        this.flats.delete(channel);
      } else {
        this.curves.set(channel, id);
      }
    }
    return problems;
  }

  /// Forgets the curves of channels not in `channels` (tracks the show no longer has).
  keepOnly(channels: Set<string>): void {
    for (const [channel, id] of this.curves) {
      if (channels.has(channel)) continue;
      this.module._avar_curve_free(id);
      this.curves.delete(channel);
      this.flats.delete(channel);
      this.handleCache.delete(channel);
    }
  }

  has(channel: string): boolean {
    return this.curves.has(channel);
  }

  sample(channel: string, t: number): number | null {
    const id = this.curves.get(channel);
    return id === undefined ? null : this.module._avar_curve_sample(id, t);
  }

  /// Values at `times`, or null when the channel has no curve.
  sampleMany(channel: string, times: Float64Array): Float64Array | null {
    const id = this.curves.get(channel);
    if (id === undefined) return null;
    const input = this.toHeap(times);
    const out = this.module._malloc(times.length * 8);
    this.module._avar_curve_sample_many(id, input, out, times.length);
    const values = this.module.HEAPF64.slice(out / 8, out / 8 + times.length);
    this.module._free(input);
    this.module._free(out);
    return values;
  }

  /// Every key's Bezier handles as the engine computes them (4 numbers a key: left time, left
  /// value, right time, right value; NaN for none), or null when the channel has no curve.
  handles(channel: string): Float64Array | null {
    const cached = this.handleCache.get(channel);
    if (cached) return cached;
    const flat = this.flats.get(channel);
    if (!flat || !this.curves.has(channel)) return null;
    const keys = Math.max(0, (flat.length - 8) / 22);
    const input = this.toHeap(flat);
    const out = this.module._malloc(Math.max(1, keys * 4) * 8);
    const count = this.module._avar_curve_handles(input, flat.length, out);
    const handles = count < 0 ? null : this.module.HEAPF64.slice(out / 8, out / 8 + count * 4);
    this.module._free(input);
    this.module._free(out);
    if (handles) this.handleCache.set(channel, handles);
    return handles;
  }

  /// One key's handle on one side as the engine computes it, or null (no curve, no handle).
  handleOf(channel: string, index: number, side: 'left' | 'right'): [number, number] | null {
    const handles = this.handles(channel);
    const t = handles?.[4 * index + (side === 'left' ? 0 : 2)];
    const v = handles?.[4 * index + (side === 'left' ? 1 : 3)];
    return t === undefined || v === undefined || Number.isNaN(t) || Number.isNaN(v) ? null : [t, v];
  }

  private toHeap(numbers: ArrayLike<number>): number {
    const address = this.module._malloc(Math.max(1, numbers.length) * 8);
    this.module.HEAPF64.set(numbers, address / 8);
    return address;
  }
}
