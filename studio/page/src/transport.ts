// The toolbar (play, pause, loop, undo, redo, save, the e-stop) and the status bar (connection,
// the run's phase, show time, faults, link counters, the last refusal).
import { formatTime } from './axis';
import type { ConnectionState } from './connection';
import { element, put, typingIn } from './dom';
import type { StudioState } from './state';

export class Transport {
  private readonly play = element<HTMLButtonElement>('play');
  private readonly loop = element<HTMLInputElement>('loop');
  private readonly undo = element<HTMLButtonElement>('undo');
  private readonly redo = element<HTMLButtonElement>('redo');
  private readonly save = element<HTMLButtonElement>('save');
  private readonly retime = element<HTMLButtonElement>('retime');
  private readonly time = element<HTMLElement>('time');
  private readonly title = element<HTMLElement>('title');
  private readonly connection = element<HTMLElement>('connection');
  private readonly phase = element<HTMLElement>('phase');
  private readonly links = element<HTMLElement>('links');
  private readonly notice = element<HTMLElement>('notice');

  constructor(private readonly state: StudioState) {
    this.play.onclick = () => void state.ask({ type: state.status?.paused === false ? 'pause' : 'play' });
    this.loop.onchange = () => void state.ask({ type: 'loop', on: this.loop.checked });
    this.undo.onclick = () => void state.ask({ type: 'undo' });
    this.redo.onclick = () => void state.ask({ type: 'redo' });
    this.save.onclick = () => void this.saveShow();
    this.retime.onclick = () => void state.ask({ type: 'retime' });
    element<HTMLButtonElement>('estop').onclick = () => void state.ask({ type: 'estop' });
    document.addEventListener('keydown', (event) => {
      if (typingIn(event)) return;
      const command = event.ctrlKey || event.metaKey;
      if (command && event.key.toLowerCase() === 'z') {
        void state.ask({ type: event.shiftKey ? 'redo' : 'undo' });
      } else if (command && event.key.toLowerCase() === 'y') {
        void state.ask({ type: 'redo' });
      } else if (command && event.key.toLowerCase() === 's') {
        void this.saveShow();
      } else if (event.key === ' ' && !command) {
        this.play.click();
      } else {
        return;
      }
      event.preventDefault();
    });
  }

  private async saveShow(): Promise<void> {
    const reply = await this.state.connection.request({ type: 'save' });
    this.state.notice = reply?.type === 'error' ? reply.message : reply?.type === 'saved' ? `saved ${reply.file}` : 'not connected';
    this.state.noticeIsProblem = reply?.type !== 'saved';
    this.state.changed();
  }

  setConnection(state: ConnectionState): void {
    this.connection.textContent =
      state === 'open' ? 'connected' : state === 'connecting' ? 'connecting…' : 'disconnected: is avar studio running? (reconnecting)';
    this.connection.className = state;
  }

  render(): void {
    const { show, status, rig } = this.state;
    if (show) {
      put(this.title, 'textContent', `${show.show.name}${show.modified ? ' •' : ''}`);
      put(this.title, 'title', show.file ?? 'no file: save is off');
      put(this.undo, 'disabled', show.undo === '');
      put(this.undo, 'title', show.undo ? `undo ${show.undo} (Ctrl+Z)` : 'nothing to undo');
      put(this.redo, 'disabled', show.redo === '');
      put(this.redo, 'title', show.redo ? `redo ${show.redo} (Ctrl+Shift+Z)` : 'nothing to redo');
      put(this.save, 'disabled', show.file === null);
    }
    const tooMuch = this.state.findings.filter((f) => f.kind === 'speed' || f.kind === 'acceleration').length;
    put(this.retime, 'disabled', tooMuch === 0);
    put(this.retime, 'textContent', tooMuch === 0 ? 'Retime' : `Retime (${tooMuch})`);
    put(
      this.retime,
      'title',
      tooMuch === 0
        ? 'every span is within its channel’s speed and acceleration'
        : `stretch the ${tooMuch} span${tooMuch === 1 ? '' : 's'} drawn red to the rig’s limits (one undo step)`,
    );
    this.retime.classList.toggle('warn', tooMuch > 0);
    if (status) {
      put(this.play, 'textContent', status.paused ? '▶ Play' : '❚❚ Pause');
      // The figure's own loop state (the show's, or what any client asked).
      if (document.activeElement !== this.loop) put(this.loop, 'checked', status.loop);
      put(this.time, 'textContent', `${formatTime(status.show_time)} / ${formatTime(status.duration, 0.1)}`);
      const fault = status.fault ? `fault: ${status.fault.cause}` : '';
      put(this.phase, 'textContent', [status.estop ? 'E-STOP' : status.phase, fault].filter(Boolean).join(' · '));
      put(this.phase, 'className', status.fault || status.estop ? 'bad' : status.phase === 'running' ? 'good' : '');
      put(
        this.links,
        'textContent',
        status.links
          .map((link) => {
            const errors = link.crc_errors + link.timeouts + link.device_errors;
            return `${link.name}: ${link.exchanges} exchanges, ${link.bytes_sent} B out, ${errors} errors`;
          })
          .join(' · '),
      );
    } else if (rig) {
      put(this.phase, 'textContent', 'no status yet');
    }
    put(this.notice, 'textContent', this.state.notice);
    put(this.notice, 'className', this.state.noticeIsProblem ? 'bad' : 'good');
  }
}
