// Pose mode: a slider per channel in its units and range, with a gauge of what the figure was
// sent (bar) and where the device says it is (tick). Dragging a slider holds the channel there
// (the figure follows through the limiter, never faster than allowed); letting go hands it back
// to the show. A digital channel is a switch held while pressed.
import { put } from './dom';
import type { RigChannel, Status } from './protocol';
import type { StudioState } from './state';

interface Row {
  channel: RigChannel;
  row: HTMLElement;
  slider: HTMLInputElement;
  readout: HTMLElement;
  bar: HTMLElement;
  measured: HTMLElement;
}

export class PosePanel {
  private rows: Row[] = [];
  private built = '';
  private shownStatus: Status | null = null;
  private shownChannel: string | null = null;

  constructor(
    private readonly root: HTMLElement,
    private readonly state: StudioState,
  ) {}

  private build(): void {
    const rig = this.state.rig;
    if (!rig) return;
    this.root.replaceChildren();
    this.rows = rig.channels.map((channel) => this.buildRow(channel));
    this.built = rig.name;
  }

  private buildRow(channel: RigChannel): Row {
    const row = document.createElement('div');
    row.className = 'pose-row';
    row.dataset.channel = channel.name;
    const name = document.createElement('button');
    name.className = 'channel-name';
    name.textContent = channel.name;
    name.title = `${channel.min} to ${channel.max} ${channel.unit}, rest ${channel.rest}; at most ${channel.max_velocity} ${channel.unit}/s`;
    name.onclick = () => {
      this.state.channel = channel.name;
      this.state.changed();
    };
    const slider = document.createElement('input');
    slider.type = 'range';
    slider.min = String(channel.min);
    slider.max = String(channel.max);
    slider.step = channel.kind === 'digital' ? '1' : String((channel.max - channel.min) / 1000);
    slider.value = String(channel.rest);
    slider.setAttribute('aria-label', `${channel.name} (${channel.unit})`);
    const hold = () => this.state.connection.send({ type: 'hold', channel: channel.name, value: Number(slider.value) });
    const release = () => {
      if (slider.dataset.holding !== 'yes') return;
      slider.dataset.holding = '';
      this.state.connection.send({ type: 'release', channel: channel.name });
    };
    slider.addEventListener('input', () => {
      slider.dataset.holding = 'yes';
      hold();
    });
    slider.addEventListener('pointerup', release);
    slider.addEventListener('blur', release);
    const gauge = document.createElement('div');
    gauge.className = 'gauge';
    const bar = document.createElement('div');
    bar.className = 'gauge-bar';
    const measured = document.createElement('div');
    measured.className = 'gauge-measured';
    gauge.append(bar, measured);
    const readout = document.createElement('span');
    readout.className = 'readout';
    row.append(name, slider, gauge, readout);
    this.root.append(row);
    return { channel, row, slider, readout, bar, measured };
  }

  render(): void {
    if (this.state.rig && this.built !== this.state.rig.name) this.build();
    const status = this.state.status;
    // Only what a new status or another channel changes: writing the page's styles at every
    // frame (a drag redraws at every frame) would lay the page out again each time.
    if (status === this.shownStatus && this.state.channel === this.shownChannel) return;
    this.shownStatus = status;
    this.shownChannel = this.state.channel;
    for (const [i, r] of this.rows.entries()) {
      r.row.classList.toggle('selected', this.state.channel === r.channel.name);
      const s = status?.channels[i];
      if (!s) continue;
      const span = r.channel.max - r.channel.min || 1;
      const fraction = (v: number) => `${(100 * Math.min(1, Math.max(0, (v - r.channel.min) / span))).toFixed(2)}%`;
      put(r.bar.style, 'width', fraction(s.command));
      put(r.measured.style, 'left', s.measured === null ? '-10px' : fraction(s.measured));
      r.row.classList.toggle('held', s.held);
      // The slider shows the figure while nobody holds it.
      if (r.slider.dataset.holding !== 'yes' && document.activeElement !== r.slider) r.slider.value = String(s.command);
      const measuredText = s.measured === null ? '' : ` · at ${s.measured.toFixed(1)}`;
      const temperature = s.temperature === null ? '' : ` · ${s.temperature.toFixed(0)} °C`;
      put(r.readout, 'textContent', `${s.command.toFixed(1)} ${r.channel.unit}${measuredText}${temperature}`);
      r.row.dataset.command = String(s.command);
      r.row.dataset.measured = String(s.measured);
    }
  }
}
