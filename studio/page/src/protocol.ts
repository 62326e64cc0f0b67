// The studio protocol's messages as the page reads them (docs/reference/studio-protocol.md).
// Times are seconds of show time; values are in the channel's units.

export interface RigChannel {
  name: string;
  unit: string;
  kind: 'analog' | 'digital';
  min: number;
  max: number;
  rest: number;
  max_velocity: number;
  max_acceleration: number;
  max_jerk: number;
}

export interface RigLink {
  name: string;
  protocol: string;
  port: string;
}

/// A rigid transform: metres, and a unit quaternion [w, x, y, z].
export interface Transform {
  xyz: [number, number, number];
  quaternion: [number, number, number, number];
}

/// A joint of the rig's kinematic tree; a movable one names the channel that drives it:
/// joint value (rad or m) = (channel value - offset) * scale.
export interface KinematicJoint {
  name: string;
  type: 'revolute' | 'prismatic' | 'fixed';
  parent: number | null;
  origin: Transform;
  axis: [number, number, number];
  channel: string | null;
  scale?: number;
  offset?: number;
}

/// What a URDF link looks like, in its link's frame (the frame of `joint` after its motion, or the
/// base frame when null); metres.
export interface Visual {
  link: string;
  joint: number | null;
  origin: Transform;
  shape: 'box' | 'cylinder' | 'sphere' | 'mesh';
  color: [number, number, number, number] | null;
  size?: [number, number, number];
  radius?: number;
  length?: number;
  /// mesh: where the studio serves the file, its format, its name in the URDF, whether it exists.
  url?: string;
  format?: 'stl' | 'dae' | 'obj' | 'unknown';
  file?: string;
  found?: boolean;
  scale?: [number, number, number];
}

export interface Kinematics {
  joints: KinematicJoint[];
  effectors: { name: string; joint: number; origin: Transform }[];
  visuals?: Visual[];
}

export interface Rig {
  name: string;
  rate_hz: number;
  channels: RigChannel[];
  links: RigLink[];
  kinematics: Kinematics | null;
}

/// A key as the show file writes it; fields the page does not read pass through unchanged.
export interface Key {
  time: number;
  value: number | boolean;
  interpolation?: string;
  left?: [number, number];
  right?: [number, number];
  left_type?: string;
  right_type?: string;
  [field: string]: unknown;
}

export interface TrackObject {
  keys: Key[];
  [field: string]: unknown;
}

export type Track = Key[] | TrackObject;

export interface Cue {
  time: number;
  [field: string]: unknown;
}

/// A clip placed on a layer: show time start..end, fading in and out (seconds).
export interface Placement {
  clip: string;
  start: number;
  end: number;
  fade_in: number;
  fade_out: number;
  [field: string]: unknown;
}

export interface Layer {
  name: string;
  blend: string;
  clips: Placement[];
  [field: string]: unknown;
}

/// An inverse-kinematics target: x, y, z (and roll, pitch, yaw) tracks, or a path.
export type TargetJson = Record<string, unknown> & { x?: Track; y?: Track; z?: Track };

export interface ShowJson {
  name: string;
  duration: number;
  loop: boolean;
  tracks: Record<string, Track>;
  cues?: Cue[];
  markers?: Marker[];
  layers?: Layer[];
  targets?: Record<string, TargetJson>;
  [field: string]: unknown;
}

/// `hello` and `show` share these fields.
export interface ShowState {
  version: number;
  file: string | null;
  modified: boolean;
  undo: string;
  redo: string;
  show: ShowJson;
}

/// The show file's names for the curve vocabulary, in order (the editor's menus).
export interface Vocabulary {
  interpolations: string[];
  easings: string[];
  handle_types: string[];
  extrapolations: string[];
}

export interface Hello extends ShowState {
  type: 'hello';
  protocol: number;
  rig: Rig;
  vocabulary: Vocabulary;
}

export interface ChannelStatus {
  name: string;
  target: number;
  command: number;
  measured: number | null;
  held: boolean;
  temperature: number | null;
  load: number | null;
  device_faults: number;
}

export interface LinkStatus {
  name: string;
  exchanges: number;
  bytes_sent: number;
  bytes_received: number;
  replies: number;
  crc_errors: number;
  timeouts: number;
  retries: number;
  device_errors: number;
  reconnects: number;
}

export interface Status {
  type: 'status';
  tick: number;
  phase: string;
  show_time: number;
  duration: number;
  paused: boolean;
  /// Whether the show starts over at its end.
  loop: boolean;
  estop: boolean;
  stopping: boolean;
  fault: { cause: string; index: number; value: number } | null;
  channels: ChannelStatus[];
  /// The show's inverse-kinematics targets: where each was asked to be this tick (metres, the
  /// rig's base frame), held by an aim or following the show.
  targets: { name: string; point: [number, number, number]; held: boolean }[];
  links: LinkStatus[];
}

/// Keys [from, from + remove) of a track became `keys` (an edit, undo or redo of existing tracks'
/// keys); the rest of the show is as it was.
export interface KeySplice {
  channel: string;
  from: number;
  remove: number;
  keys: Key[];
}

export interface KeysChange {
  type: 'keys';
  version: number;
  file: string | null;
  modified: boolean;
  undo: string;
  redo: string;
  tracks: KeySplice[];
}

export interface Curves {
  type: 'curves';
  version: number;
  format: number;
  tracks: Record<string, number[]>;
}

/// A span of a track that asks more than its channel allows (`avar check`'s findings).
export interface Finding {
  kind: 'speed' | 'acceleration' | 'range' | 'jump';
  channel: string;
  unit: string;
  t0: number;
  t1: number;
  required: number;
  allowed: number;
  text: string;
}

export interface Check {
  type: 'check';
  version: number;
  findings: Finding[];
}

/// The sound a track made from audio follows: the lowest and highest sample of every `bucket`
/// seconds of it, full scale +-1, from show time `start`.
export interface WaveformTrack {
  channel: string;
  file: string;
  start: number;
  duration: number;
  bucket: number;
  peaks: number[];
}

export interface Waveform {
  type: 'waveform';
  tracks: WaveformTrack[];
}

export type ServerMessage =
  | Check
  | Waveform
  | Hello
  | Status
  | Curves
  | ({ type: 'show' } & ShowState)
  | KeysChange
  | { type: 'ok'; request: string }
  | { type: 'error'; request: string; message: string }
  | { type: 'saved'; file: string }
  | { type: 'refused'; command: string; outcome: string; channel?: string };

export type Edit =
  | { op: 'add'; channel: string; keys: Key[] }
  | { op: 'delete'; channel: string; keys: number[] }
  | { op: 'move'; channel: string; keys: number[]; dt: number; dv: number }
  | { op: 'set'; channel: string; key: number; value: Key }
  | { op: 'insert_time'; at: number; length: number }
  | { op: 'delete_time'; from: number; to: number }
  | { op: 'markers'; markers: Marker[] };

/// A named point of show time (the show file's `markers:`): for navigating; it plays nothing.
export interface Marker {
  time: number;
  name: string;
}

/// The keys of a track, whichever form the show file gave it.
export function trackKeys(track: Track | undefined): Key[] {
  if (!track) return [];
  return Array.isArray(track) ? track : track.keys;
}

export function numericValue(key: Key): number {
  return typeof key.value === 'boolean' ? (key.value ? 1 : 0) : key.value;
}

/// The index of the first key at or after `t` (keys.length when none): keys are in time order.
export function firstKeyAtOrAfter(keys: Key[], t: number): number {
  let lo = 0;
  let hi = keys.length;
  while (lo < hi) {
    const mid = (lo + hi) >>> 1;
    if (keys[mid]!.time < t) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}
