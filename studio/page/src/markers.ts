// The show's markers: named points of show time on the dope sheet's ruler. M adds one at the
// playhead, [ and ] jump the playhead to the one before or after it, double-clicking one on the
// ruler renames it (an empty name deletes it), Shift+M deletes the one at the playhead. Every
// change is one `markers` edit (the whole new list), undone like any other.
import type { TimeAxis } from './axis';
import { typingIn } from './dom';
import type { Marker } from './protocol';
import type { StudioState } from './state';

/// How close (CSS pixels) a double-click must be to a marker's line to take it.
const REACH = 6;

export class Markers {
  constructor(private readonly state: StudioState) {
    window.addEventListener('keydown', (e) => {
      if (typingIn(e) || e.ctrlKey || e.metaKey || e.altKey) return;
      if (e.key === 'm') void this.add();
      else if (e.key === 'M') void this.removeAtPlayhead();
      else if (e.key === '[' || e.key === ']') this.jump(e.key === ']' ? 1 : -1);
      else return;
      e.preventDefault();
    });
  }

  list(): Marker[] {
    return this.state.show?.show.markers ?? [];
  }

  private playhead(): number {
    return this.state.status?.show_time ?? 0;
  }

  private set(markers: Marker[]): Promise<boolean> {
    return this.state.edit([{ op: 'markers', markers }]);
  }

  /// A marker at the playhead, named "marker N" with the first N not taken.
  async add(): Promise<boolean> {
    const markers = this.list();
    let n = markers.length + 1;
    while (markers.some((m) => m.name === `marker ${n}`)) n++;
    const time = Math.round(Math.min(Math.max(this.playhead(), 0), this.state.duration()) * 1000) / 1000;
    return this.set([...markers, { time, name: `marker ${n}` }]);
  }

  /// Deletes the marker nearest the playhead, when one is within a tenth of a second of it.
  private async removeAtPlayhead(): Promise<void> {
    const markers = this.list();
    const t = this.playhead();
    const near = markers.reduce<number>((best, m, i) => {
      const d = Math.abs(m.time - t);
      return d <= 0.1 && (best < 0 || d < Math.abs((markers[best]?.time ?? 0) - t)) ? i : best;
    }, -1);
    if (near >= 0) await this.set(markers.filter((_, i) => i !== near));
  }

  /// Seeks to the next marker after the playhead (direction 1) or the one before it (-1).
  private jump(direction: 1 | -1): void {
    const t = this.playhead();
    const times = this.list().map((m) => m.time);
    const next = direction > 0 ? times.find((x) => x > t + 1e-6) : [...times].reverse().find((x) => x < t - 1e-6);
    if (next !== undefined) void this.state.ask({ type: 'seek', time: next });
  }

  /// The marker drawn within reach of x on `axis`, if any.
  at(axis: TimeAxis, x: number): number {
    return this.list().findIndex((m) => Math.abs(axis.x(m.time) - x) <= REACH);
  }

  /// Asks for marker `index`'s new name; an empty one deletes it.
  async rename(index: number): Promise<void> {
    const markers = this.list();
    const marker = markers[index];
    if (!marker) return;
    const name = window.prompt('Marker name (empty: delete the marker)', marker.name);
    if (name === null || name === marker.name) return;
    const rest = markers.filter((_, i) => i !== index);
    await this.set(name.trim() === '' ? rest : [...rest, { time: marker.time, name: name.trim() }]);
  }
}
