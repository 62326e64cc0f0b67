// Show time to pixels and back over the state's visible stretch, and the tick spacing of a ruler
// that stays readable from 0.01 s to hours.

export class TimeAxis {
  constructor(
    readonly t0: number,
    readonly t1: number,
    readonly x0: number,
    readonly x1: number,
  ) {}

  x(t: number): number {
    return this.x0 + ((t - this.t0) / (this.t1 - this.t0)) * (this.x1 - this.x0);
  }

  t(x: number): number {
    return this.t0 + ((x - this.x0) / (this.x1 - this.x0)) * (this.t1 - this.t0);
  }

  secondsPerPixel(): number {
    return (this.t1 - this.t0) / (this.x1 - this.x0);
  }
}

/// A round step (1, 2 or 5 times a power of ten) so that ticks are at least `minimum` apart.
export function tickStep(minimum: number): number {
  const power = 10 ** Math.floor(Math.log10(minimum));
  for (const m of [1, 2, 5, 10]) if (m * power >= minimum) return m * power;
  return 10 * power;
}

/// "1:02:03.5", "2:03.25", "3.125": as few digits as the step needs.
export function formatTime(t: number, step = 0.001): string {
  const digits = Math.max(0, Math.min(3, Math.ceil(-Math.log10(step) - 1e-9)));
  const sign = t < 0 ? '-' : '';
  const a = Math.abs(t);
  const hours = Math.floor(a / 3600);
  const minutes = Math.floor((a % 3600) / 60);
  const seconds = (a % 60).toFixed(digits);
  if (hours > 0) return `${sign}${hours}:${String(minutes).padStart(2, '0')}:${seconds.padStart(digits ? digits + 3 : 2, '0')}`;
  if (minutes > 0) return `${sign}${minutes}:${seconds.padStart(digits ? digits + 3 : 2, '0')}`;
  return `${sign}${seconds}`;
}

/// Zooms the stretch [t0, t1] by `factor` around `at`, keeping it between 0.01 s and 100 h.
export function zoomView(view: { t0: number; t1: number }, at: number, factor: number): void {
  const span = Math.min(360000, Math.max(0.01, (view.t1 - view.t0) * factor));
  const f = (at - view.t0) / (view.t1 - view.t0);
  view.t0 = at - f * span;
  view.t1 = view.t0 + span;
}

/// A canvas sized to its element in device pixels; the context draws in CSS pixels.
export function fitCanvas(canvas: HTMLCanvasElement): CanvasRenderingContext2D {
  const ratio = window.devicePixelRatio || 1;
  const width = Math.max(1, Math.round(canvas.clientWidth * ratio));
  const height = Math.max(1, Math.round(canvas.clientHeight * ratio));
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  const context = canvas.getContext('2d');
  if (!context) throw new Error('this browser gives no 2-D canvas');
  context.setTransform(ratio, 0, 0, ratio, 0, 0);
  return context;
}

const themeColors = new Map<string, string>();
// The theme follows the system's light or dark preference: its colours are read again then.
window.matchMedia('(prefers-color-scheme: dark)').addEventListener('change', () => themeColors.clear());

/// The theme's colour named `name` (a CSS custom property of the page), for canvas drawing. Read
/// once (reading computed style costs more than drawing a key, and a redraw asks thousands).
export function themeColor(name: string): string {
  let color = themeColors.get(name);
  if (color === undefined) {
    color = getComputedStyle(document.documentElement).getPropertyValue(name).trim() || '#888';
    themeColors.set(name, color);
  }
  return color;
}

/// The playhead: a vertical line at show time `t`, where it is right of `left`.
export function drawPlayhead(g: CanvasRenderingContext2D, axis: TimeAxis, t: number, left: number, height: number): void {
  const x = Math.round(axis.x(t)) + 0.5;
  if (x < left) return;
  g.strokeStyle = themeColor('--playhead');
  g.lineWidth = 2;
  g.beginPath();
  g.moveTo(x, 0);
  g.lineTo(x, height);
  g.stroke();
}
