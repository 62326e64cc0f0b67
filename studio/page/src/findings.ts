// The feasibility check's findings in words, for tooltips and the graph editor.
import type { Finding } from './protocol';

const round = (v: number) => (Math.abs(v) >= 100 ? v.toFixed(0) : v.toPrecision(3));

/// "speed 460 deg/s, allowed 300 deg/s (7.8–7.85 s)".
export function describeFinding(f: Finding): string {
  const span = `(${round(f.t0)}–${round(f.t1)} s)`;
  switch (f.kind) {
    case 'speed':
      return `speed ${round(f.required)} ${f.unit}/s, allowed ${round(f.allowed)} ${f.unit}/s ${span}`;
    case 'acceleration':
      return `acceleration ${round(f.required)} ${f.unit}/s², allowed ${round(f.allowed)} ${f.unit}/s² ${span}`;
    case 'range':
      return `reaches ${round(f.required)} ${f.unit}, the range ends at ${round(f.allowed)} ${f.unit} ${span}`;
    case 'jump':
      return `jumps by ${round(f.required)} ${f.unit} at once (step); the limiter shapes it ${span}`;
  }
}
