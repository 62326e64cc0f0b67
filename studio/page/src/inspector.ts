// The key inspector, between the dope sheet and the graph editor: the selected key's exact time
// and value, its interpolation and easing, and its handle types, each applied as one edit (the
// studio refuses what would not build, and says why in the status bar). Beside it: copy and paste
// keys at the playhead, and ripple insert or delete time there.
import { element, put, typingIn } from './dom';
import type { Edit, Key } from './protocol';
import { numericValue } from './protocol';
import type { StudioState } from './state';

/// The one key the inspector shows: the first selected key of the selected channel, or the first
/// selected key anywhere.
function inspected(state: StudioState): { channel: string; index: number; key: Key } | null {
  const pick = (channel: string) => {
    const set = state.selection.get(channel);
    if (!set || set.size === 0) return null;
    const index = Math.min(...set);
    const key = state.keys(channel)[index];
    return key ? { channel, index, key } : null;
  };
  if (state.channel) {
    const found = pick(state.channel);
    if (found) return found;
  }
  for (const channel of state.selection.keys()) {
    const found = pick(channel);
    if (found) return found;
  }
  return null;
}

export class Inspector {
  private readonly label = element<HTMLElement>('key-label');
  private readonly time = element<HTMLInputElement>('key-time');
  private readonly value = element<HTMLInputElement>('key-value');
  private readonly interpolation = element<HTMLSelectElement>('key-interpolation');
  private readonly easing = element<HTMLSelectElement>('key-easing');
  private readonly leftType = element<HTMLSelectElement>('key-left-type');
  private readonly rightType = element<HTMLSelectElement>('key-right-type');
  private readonly timeLength = element<HTMLInputElement>('time-length');
  private vocabularyShown = false;

  constructor(private readonly state: StudioState) {
    const change = (update: (key: Key) => Key) => () => void this.setKey(update);
    this.time.onchange = change((k) => ({ ...k, time: Number(this.time.value) }));
    this.value.onchange = change((k) => ({ ...k, value: Number(this.value.value) }));
    this.interpolation.onchange = change((k) => ({ ...k, interpolation: this.interpolation.value }));
    this.easing.onchange = change((k) => ({ ...k, easing: this.easing.value }));
    this.leftType.onchange = change((k) => withHandleType(k, 'left', this.leftType.value, this.computedHandle('left')));
    this.rightType.onchange = change((k) => withHandleType(k, 'right', this.rightType.value, this.computedHandle('right')));
    element<HTMLButtonElement>('insert-time').onclick = () => void this.rippleTime('insert');
    element<HTMLButtonElement>('delete-time').onclick = () => void this.rippleTime('delete');
    document.addEventListener('keydown', (event) => {
      if (typingIn(event)) return;
      if (!(event.ctrlKey || event.metaKey)) return;
      if (event.key.toLowerCase() === 'c') this.copy();
      else if (event.key.toLowerCase() === 'v') void this.paste();
      else return;
      event.preventDefault();
    });
  }

  /// The inspected key's handle on one side as the engine computes it now.
  private computedHandle(side: 'left' | 'right'): [number, number] | null {
    const at = inspected(this.state);
    return at ? this.state.engine.handleOf(at.channel, at.index, side) : null;
  }

  private async setKey(update: (key: Key) => Key): Promise<void> {
    const at = inspected(this.state);
    if (!at) return;
    if (!(await this.state.edit([{ op: 'set', channel: at.channel, key: at.index, value: update(at.key) }]))) this.render(true);
  }

  /// Copies the selected keys, their times from the earliest of them.
  copy(): void {
    let earliest = Infinity;
    for (const [channel, set] of this.state.selection)
      for (const i of set) earliest = Math.min(earliest, this.state.keys(channel)[i]?.time ?? Infinity);
    if (!Number.isFinite(earliest)) return;
    this.state.clipboard = new Map();
    for (const [channel, set] of this.state.selection) {
      const keys = [...set].sort((a, b) => a - b).flatMap((i) => this.state.keys(channel)[i] ?? []);
      if (keys.length > 0) this.state.clipboard.set(channel, keys.map((k) => shiftKey(k, -earliest)));
    }
    const count = [...this.state.clipboard.values()].reduce((n, keys) => n + keys.length, 0);
    this.state.notice = `copied ${count} key${count === 1 ? '' : 's'}`;
    this.state.noticeIsProblem = false;
    this.state.changed();
  }

  /// Pastes the copied keys at the playhead, as one undo step.
  async paste(): Promise<void> {
    const at = this.state.status?.show_time ?? 0;
    const edits: Edit[] = [...this.state.clipboard].map(([channel, keys]) => ({
      op: 'add',
      channel,
      keys: keys.map((k) => shiftKey(k, at)),
    }));
    if (edits.length > 0) await this.state.edit(edits);
  }

  private async rippleTime(kind: 'insert' | 'delete'): Promise<void> {
    const at = this.state.status?.show_time ?? 0;
    const length = Number(this.timeLength.value);
    if (!(length > 0)) {
      this.state.notice = 'the length of time to insert or delete must be more than 0 s';
      this.state.changed();
      return;
    }
    await this.state.edit([
      kind === 'insert' ? { op: 'insert_time', at, length } : { op: 'delete_time', from: at, to: at + length },
    ]);
  }

  render(force = false): void {
    if (!this.vocabularyShown && this.state.vocabulary.interpolations.length > 0) {
      fill(this.interpolation, this.state.vocabulary.interpolations);
      fill(this.easing, this.state.vocabulary.easings);
      fill(this.leftType, this.state.vocabulary.handle_types);
      fill(this.rightType, this.state.vocabulary.handle_types);
      this.vocabularyShown = true;
    }
    const at = inspected(this.state);
    for (const control of [this.time, this.value, this.interpolation, this.easing, this.leftType, this.rightType])
      put(control, 'disabled', at === null);
    if (!at) {
      put(this.label, 'textContent', 'no key selected');
      for (const input of [this.time, this.value]) put(input, 'value', '');
      for (const select of [this.interpolation, this.easing, this.leftType, this.rightType]) put(select, 'selectedIndex', -1);
      return;
    }
    put(this.label, 'textContent', `${at.channel} key ${at.index}`);
    // A field being typed in keeps what the user types until it is applied.
    const show = (input: HTMLInputElement | HTMLSelectElement, text: string) => {
      if (force || document.activeElement !== input) put(input, 'value', text);
    };
    show(this.time, String(at.key.time));
    show(this.value, String(numericValue(at.key)));
    show(this.interpolation, at.key.interpolation ?? 'linear');
    show(this.easing, String(at.key.easing ?? 'auto'));
    const given = (side: 'left' | 'right') => at.key[`${side}_type`] ?? (at.key[side] ? 'free' : 'auto_clamped');
    show(this.leftType, String(given('left')));
    show(this.rightType, String(given('right')));
  }
}

function fill(select: HTMLSelectElement, names: string[]): void {
  select.replaceChildren(...names.map((name) => new Option(name.replaceAll('_', ' '), name)));
}

/// A key moved by `dt` seconds, with its handles.
function shiftKey(key: Key, dt: number): Key {
  const moved: Key = { ...key, time: key.time + dt };
  if (key.left) moved.left = [key.left[0] + dt, key.left[1]];
  if (key.right) moved.right = [key.right[0] + dt, key.right[1]];
  return moved;
}

/// A key with one side's handle type set. An automatic or vector side is computed, so a handle
/// given for it is dropped; a free or aligned side needs one, so it keeps the key's own or takes
/// the one the engine computed for the side until now (the curve does not jump).
function withHandleType(key: Key, side: 'left' | 'right', type: string, computed: [number, number] | null): Key {
  const changed: Key = { ...key, [`${side}_type`]: type };
  if (type === 'auto' || type === 'auto_clamped' || type === 'vector') delete changed[side];
  else if (!changed[side] && computed) changed[side] = computed;
  return changed;
}
