// avar's curve engine compiled to WebAssembly (avar_curves.js, loaded by index.html): the page
// builds every track from the server's flat keys (the `curves` message) and samples it exactly
// as the figure does, bit for bit. No curve maths lives in TypeScript.

interface CurveModule {
  _avar_curve_build(flat: number, count: number): number;
  _avar_curve_free(id: number): void;
  _avar_curve_sample(id: number, t: number): number;
  _avar_curve_sample_many(id: number, times: number, out: number, count: number): void;
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
  private constructor(private readonly module: CurveModule) {}

  static async load(): Promise<CurveEngine> {
    if (!window.AvarCurves) throw new Error('the curve engine (avar_curves.js) did not load');
    return new CurveEngine(await window.AvarCurves());
  }

  /// Replaces every curve with the tracks of a `curves` message; the channels whose keys the
  /// engine refused, with its reason (the server built them, so this is not expected).
  setTracks(tracks: Record<string, number[]>): string[] {
    for (const id of this.curves.values()) this.module._avar_curve_free(id);
    this.curves.clear();
    const problems: string[] = [];
    for (const [channel, flat] of Object.entries(tracks)) {
      const address = this.toHeap(flat);
      const id = this.module._avar_curve_build(address, flat.length);
      this.module._free(address);
      if (id < 0) problems.push(`${channel}: ${this.module.UTF8ToString(this.module._avar_error())}`);
      else this.curves.set(channel, id);
    }
    return problems;
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

  private toHeap(numbers: ArrayLike<number>): number {
    const address = this.module._malloc(Math.max(1, numbers.length) * 8);
    this.module.HEAPF64.set(numbers, address / 8);
    return address;
  }
}
