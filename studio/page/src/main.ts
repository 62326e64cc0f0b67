// avar studio's page: connects to the studio, loads the curve engine, and wires the views.
import { Connection } from './connection';
import { element } from './dom';
import { CurveEngine } from './engine';
import { GraphEditor } from './graph';
import { Inspector } from './inspector';
import { PosePanel } from './pose';
import { Preview } from './preview';
import type { ServerMessage } from './protocol';
import { StudioState } from './state';
import { DopeSheet } from './timeline';
import { Transport } from './transport';

declare global {
  interface Window {
    /// The page's state and views, for the browser's console and the page's tests.
    avarStudio?: { state: StudioState; dope: DopeSheet; graph: GraphEditor; preview: Preview };
  }
}

async function main(): Promise<void> {
  const engine = await CurveEngine.load();
  let transport: Transport | null = null;
  let state: StudioState | null = null;
  const receive = (message: ServerMessage) => {
    if (!state) return;
    switch (message.type) {
      case 'hello':
        state.takeHello(message);
        document.body.dataset.ready = 'yes';
        break;
      case 'show':
        state.takeShow(message);
        break;
      case 'keys':
        state.takeKeys(message);
        break;
      case 'status':
        state.status = message;
        state.changed();
        break;
      case 'refused':
        state.notice = `the figure refused ${message.command}${message.channel ? ` on ${message.channel}` : ''}: ${message.outcome}`;
        state.noticeIsProblem = true;
        state.changed();
        break;
      default:
        break;
    }
  };
  const connection = new Connection(receive, (s) => transport?.setConnection(s));
  state = new StudioState(connection, engine);
  transport = new Transport(state);
  const pose = new PosePanel(element('pose'), state);
  const dope = new DopeSheet(element<HTMLCanvasElement>('dopesheet'), state);
  const graph = new GraphEditor(element<HTMLCanvasElement>('graph'), state);
  const inspector = new Inspector(state);
  const preview = new Preview(element<HTMLCanvasElement>('preview'), element('preview-message'), state);
  state.onChange(() => {
    transport?.render();
    pose.render();
    dope.render();
    graph.render();
    inspector.render();
    preview.render();
  });
  window.avarStudio = { state, dope, graph, preview };
  connection.open();
}

main().catch((error: unknown) => {
  const notice = document.getElementById('notice');
  if (notice) notice.textContent = `the page could not start: ${String(error)}`;
  throw error;
});
