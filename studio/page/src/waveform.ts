// A sound's outline (the `waveform` message) drawn under a track: a vertical line per pixel
// column from the lowest to the highest sample the column covers.
import { themeColor, type TimeAxis } from './axis';
import type { WaveformTrack } from './protocol';

/// Draws `wave` between x = left and right, centred in [top, top + height].
export function drawWaveform(
  g: CanvasRenderingContext2D,
  axis: TimeAxis,
  wave: WaveformTrack,
  left: number,
  right: number,
  top: number,
  height: number,
): void {
  const buckets = wave.peaks.length / 2;
  const from = Math.max(left, Math.floor(axis.x(wave.start)));
  const to = Math.min(right, Math.ceil(axis.x(wave.start + wave.duration)));
  const middle = top + height / 2;
  g.fillStyle = themeColor('--wave');
  for (let x = from; x < to; x++) {
    const b0 = Math.max(0, Math.floor((axis.t(x) - wave.start) / wave.bucket));
    const b1 = Math.min(buckets, Math.max(b0 + 1, Math.ceil((axis.t(x + 1) - wave.start) / wave.bucket)));
    let low = 0;
    let high = 0;
    for (let b = b0; b < b1; b++) {
      low = Math.min(low, wave.peaks[2 * b] ?? 0);
      high = Math.max(high, wave.peaks[2 * b + 1] ?? 0);
    }
    const y0 = middle - (high * height) / 2;
    g.fillRect(x, y0, 1, Math.max(1, ((high - low) * height) / 2));
  }
}
