// The page's one WebSocket to the studio: messages in and out, reconnecting when the server
// comes back. The token of a studio listening beyond loopback is taken from the page's URL.
import type { ServerMessage } from './protocol';

/// The one reply the server sends to each message, in the order of the messages.
export type Reply = Extract<ServerMessage, { type: 'ok' | 'error' | 'curves' | 'check' | 'saved' | 'waveform' }>;
const isReply = (m: ServerMessage): m is Reply =>
  m.type === 'ok' || m.type === 'error' || m.type === 'curves' || m.type === 'check' || m.type === 'saved' || m.type === 'waveform';

export type ConnectionState = 'connecting' | 'open' | 'closed';

export class Connection {
  private socket: WebSocket | null = null;
  private retry = 0;
  private waiting: ((reply: Reply | null) => void)[] = [];
  private idleWaiters: (() => void)[] = [];

  constructor(
    private readonly onMessage: (message: ServerMessage) => void,
    private readonly onState: (state: ConnectionState) => void,
  ) {}

  open(): void {
    const token = new URLSearchParams(location.search).get('token');
    const scheme = location.protocol === 'https:' ? 'wss:' : 'ws:';
    const url = `${scheme}//${location.host}/ws${token ? `?token=${encodeURIComponent(token)}` : ''}`;
    this.onState('connecting');
    const socket = new WebSocket(url);
    this.socket = socket;
    socket.onopen = () => {
      this.retry = 0;
      this.onState('open');
    };
    socket.onmessage = (event) => {
      if (typeof event.data !== 'string') return;
      const message = JSON.parse(event.data) as ServerMessage;
      if (isReply(message)) this.waiting.shift()?.(message);
      this.onMessage(message);
      if (this.waiting.length === 0) for (const resume of this.idleWaiters.splice(0)) resume();
    };
    socket.onclose = () => {
      this.socket = null;
      for (const answer of this.waiting.splice(0)) answer(null);
      for (const resume of this.idleWaiters.splice(0)) resume();
      this.onState('closed');
      // The studio was stopped or restarted: try again, less and less often (at most every 5 s).
      this.retry = Math.min(this.retry + 1, 10);
      setTimeout(() => this.open(), Math.min(5000, 250 * this.retry));
    };
  }

  /// Sends one message; false when there is no connection (nothing is queued: a pose or an edit
  /// sent later than asked would surprise).
  send(message: object): boolean {
    return this.request(message) !== null;
  }

  /// Messages sent and not answered yet.
  inFlight(): number {
    return this.waiting.length;
  }

  /// Resolves once every message sent so far is answered (at once when none is waiting).
  whenIdle(): Promise<void> {
    if (this.waiting.length === 0) return Promise.resolve();
    return new Promise((resume) => this.idleWaiters.push(resume));
  }

  /// Sends one message and resolves with its reply (null: the connection closed first); null at
  /// once when there is no connection.
  request(message: object): Promise<Reply | null> | null {
    if (!this.socket || this.socket.readyState !== WebSocket.OPEN) return null;
    const reply = new Promise<Reply | null>((resolve) => this.waiting.push(resolve));
    this.socket.send(JSON.stringify(message));
    return reply;
  }
}
