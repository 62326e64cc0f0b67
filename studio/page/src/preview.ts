// The 3-D preview: the rig's kinematic tree drawn as its URDF's looks where the rig has them
// (figure_visuals.ts: boxes, cylinders, spheres, meshes) and as simple link shapes otherwise (a
// sphere at each joint, a rod to the next, a marker at each effector), posed every status by
// where the device says each joint's channel is (what was sent, where the device reports
// nothing). Orbit with the left button, zoom with the wheel, pan with the right button; click a
// joint to select its channel's track. The show's inverse-kinematics targets are drawn as yellow balls where the figure is
// asked to reach or look; drag one and the target is held there (the joints follow through the
// rig's IK, within their limits) until it is let go, when the show's path takes it back. A rig
// without a kinematics section has no preview: its gauges show every channel.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { put } from './dom';
import { addVisuals, placed } from './figure_visuals';
import type { KinematicJoint, Kinematics } from './protocol';
import type { StudioState } from './state';

interface EffectorView {
  name: string;
  frame: THREE.Group;
}

interface JointView {
  joint: KinematicJoint;
  /// The joint's frame at zero in its parent's (origin), and the motion about its axis inside it.
  motion: THREE.Group;
  ball: THREE.Mesh;
}

/// A rod from the frame's origin to `to` (in that frame), `radius` thick.
function rod(to: THREE.Vector3, radius: number, material: THREE.Material): THREE.Mesh | null {
  const length = to.length();
  if (length < 1e-6) return null;
  const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, length, 16), material);
  mesh.position.copy(to).multiplyScalar(0.5);
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), to.clone().normalize());
  return mesh;
}

export class Preview {
  private renderer: THREE.WebGLRenderer | null = null;
  private readonly scene = new THREE.Scene();
  private readonly camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
  private controls: OrbitControls | null = null;
  private joints: JointView[] = [];
  private figure: THREE.Group | null = null;
  private targets: THREE.Mesh[] = [];
  /// A line from each target's effector to the target: what the figure looks at or reaches for.
  private sightLines: THREE.Line[] = [];
  private readonly sightMaterial = new THREE.LineDashedMaterial({ color: 0xffd54f, dashSize: 0.02, gapSize: 0.015 });
  private targetRadius = 0.02;
  private aiming: { index: number; plane: THREE.Plane; sending: Promise<void> | null; pending: THREE.Vector3 | null } | null = null;
  private readonly targetMaterial = new THREE.MeshStandardMaterial({ color: 0xffd54f, emissive: 0x443300 });
  private readonly heldMaterial = new THREE.MeshStandardMaterial({ color: 0xff8a3d, emissive: 0x552200 });
  private effectors: EffectorView[] = [];
  private built: Kinematics | null = null;
  /// The simple shapes' rods: hidden while the figure's own visuals draw it.
  private rods: THREE.Mesh[] = [];
  /// What the figure's visuals came to: how many were drawn, and why any mesh was not.
  private visuals: Promise<{ drawn: number; problems: string[] }> = Promise.resolve({ drawn: 0, problems: [] });
  private visualProblems: string[] = [];
  /// Each URDF link's frame, by the link's name.
  private linkFrames = new Map<string, THREE.Object3D>();
  private readonly selectedMaterial = new THREE.MeshStandardMaterial({ color: 0xffb13b });
  private readonly jointMaterial = new THREE.MeshStandardMaterial({ color: 0x5fb3f9 });
  private readonly linkMaterial = new THREE.MeshStandardMaterial({ color: 0xb8c0cc, metalness: 0.2, roughness: 0.6 });

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly message: HTMLElement,
    private readonly state: StudioState,
  ) {
    try {
      this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    } catch {
      this.renderer = null;
    }
    this.scene.background = new THREE.Color(0x181b20);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x30343c, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(2, 3, 4);
    this.scene.add(sun);
    if (this.renderer) {
      this.controls = new OrbitControls(this.camera, canvas);
      this.controls.addEventListener('change', () => this.draw());
      canvas.addEventListener('click', (e) => this.pick(e));
      // Capture: before OrbitControls' own pointerdown, so that a press on a target does not orbit.
      canvas.addEventListener('pointerdown', (e) => this.startAim(e), { capture: true });
      canvas.addEventListener('pointermove', (e) => this.moveAim(e));
      canvas.addEventListener('pointerup', (e) => this.endAim(e));
      new ResizeObserver(() => this.draw()).observe(canvas);
    }
  }

  private build(kinematics: Kinematics): void {
    this.built = kinematics;
    const figure = new THREE.Group();
    // The rig's frame is z-up (x forward, y left); three.js draws y-up.
    figure.rotation.x = -Math.PI / 2;
    this.scene.add(figure);
    this.figure = figure;
    this.targets = [];
    this.sightLines = [];
    const grid = new THREE.GridHelper(2, 20, 0x3d4654, 0x2a2f37);
    this.scene.add(grid);

    // Size the shapes to the figure: a tenth of its longest offset, at least a centimetre.
    const reach = Math.max(0.05, ...kinematics.joints.map((j) => Math.hypot(...j.origin.xyz)));
    const radius = Math.max(0.004, reach * 0.06);
    this.targetRadius = radius * 1.3;
    this.joints = [];
    this.effectors = [];
    this.rods = [];
    this.visualProblems = [];
    // With the figure's own looks, the joints are small handles on it and the rods give way.
    const looks = kinematics.visuals ?? [];
    const ballRadius = looks.length > 0 ? radius * 0.45 : radius;
    const addRod = (parent: THREE.Object3D, to: THREE.Vector3, thickness: number): void => {
      const link = rod(to, thickness, this.linkMaterial);
      if (!link) return;
      link.visible = looks.length === 0;
      parent.add(link);
      this.rods.push(link);
    };
    for (const joint of kinematics.joints) {
      const parent = joint.parent === null ? figure : (this.joints[joint.parent]?.motion ?? figure);
      const frame = placed(joint.origin);
      addRod(parent, frame.position.clone(), radius * 0.5);
      parent.add(frame);
      const motion = new THREE.Group();
      frame.add(motion);
      const ball = new THREE.Mesh(new THREE.SphereGeometry(ballRadius, 24, 16), this.jointMaterial);
      ball.userData.joint = this.joints.length;
      motion.add(ball);
      this.joints.push({ joint, motion, ball });
    }
    for (const effector of kinematics.effectors) {
      const parent = this.joints[effector.joint]?.motion ?? figure;
      const frame = placed(effector.origin);
      addRod(parent, frame.position.clone(), radius * 0.35);
      parent.add(frame);
      frame.add(new THREE.AxesHelper(radius * 4));
      this.effectors.push({ name: effector.name, frame });
    }
    this.frame();
    if (looks.length > 0) {
      const frameOf = (joint: number | null): THREE.Object3D => (joint === null ? figure : (this.joints[joint]?.motion ?? figure));
      this.linkFrames = new Map(looks.map((look) => [look.link, frameOf(look.joint)]));
      const load = addVisuals(looks, frameOf, () => this.draw());
      this.visuals = load.done.then((problems) => {
        // A mesh that could not be had: the simple shapes draw the figure too, and the note says why.
        this.visualProblems = problems;
        if (problems.length > 0)
          for (const link of this.rods) link.visible = true;
        this.frame();
        this.render();
        return { drawn: load.objects.length, problems };
      });
    } else {
      this.visuals = Promise.resolve({ drawn: 0, problems: [] });
    }
  }

  /// Settles when the figure's visuals are drawn: how many, and why any mesh was not (for tests).
  visualsReady(): Promise<{ drawn: number; problems: string[] }> {
    return this.visuals;
  }

  /// Frames the figure and its targets: looks at their middle from the front-left, above.
  private frame(): void {
    if (!this.figure) return;
    const box = new THREE.Box3().setFromObject(this.figure);
    const centre = box.getCenter(new THREE.Vector3());
    const size = Math.max(0.1, box.getSize(new THREE.Vector3()).length());
    this.camera.position.set(centre.x + size * 0.55, centre.y + size * 0.4, centre.z + size * 0.7);
    this.controls?.target.copy(centre);
    this.controls?.update();
  }

  /// A joint's value (rad or m) from where its channel is, as the status says.
  jointValue(name: string): number | null {
    const view = this.joints.find((j) => j.joint.name === name);
    if (!view?.joint.channel) return null;
    const index = this.state.rig?.channels.findIndex((c) => c.name === view.joint.channel) ?? -1;
    const channel = this.state.status?.channels[index];
    if (!channel) return null;
    const at = channel.measured ?? channel.command;
    return (at - (view.joint.offset ?? 0)) * (view.joint.scale ?? 1);
  }

  /// Where a joint or an effector is drawn, in the canvas's CSS pixels (for tests and tooltips).
  screenPosition(name: string): { x: number; y: number } | null {
    const object = this.joints.find((j) => j.joint.name === name)?.ball ?? this.effectors.find((e) => e.name === name)?.frame;
    if (!object) return null;
    const p = object.getWorldPosition(new THREE.Vector3()).project(this.camera);
    return { x: ((p.x + 1) / 2) * this.canvas.clientWidth, y: ((1 - p.y) / 2) * this.canvas.clientHeight };
  }

  private ray(event: MouseEvent): THREE.Raycaster {
    const ray = new THREE.Raycaster();
    const at = new THREE.Vector2((event.offsetX / this.canvas.clientWidth) * 2 - 1, -(event.offsetY / this.canvas.clientHeight) * 2 + 1);
    ray.setFromCamera(at, this.camera);
    return ray;
  }

  /// A press on a target starts holding it: the pointer drags it over the plane through it that
  /// faces the camera.
  private startAim(event: PointerEvent): void {
    const hit = this.ray(event).intersectObjects(this.targets)[0];
    if (!hit) return;
    const index = hit.object.userData.target as number;
    const normal = this.camera.getWorldDirection(new THREE.Vector3());
    this.aiming = {
      index,
      plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, hit.object.getWorldPosition(new THREE.Vector3())),
      sending: null,
      pending: null,
    };
    if (this.controls) this.controls.enabled = false;
    this.canvas.setPointerCapture(event.pointerId);
    event.stopPropagation();
  }

  private moveAim(event: PointerEvent): void {
    const aiming = this.aiming;
    if (!aiming || !this.figure) return;
    const world = this.ray(event).ray.intersectPlane(aiming.plane, new THREE.Vector3());
    if (!world) return;
    aiming.pending = this.figure.worldToLocal(world);
    if (!aiming.sending)
      aiming.sending = this.sendAim(aiming).finally(() => {
        aiming.sending = null;
      });
  }

  /// One aim in flight at a time; the newest pointer position is sent when it is answered.
  private async sendAim(aiming: NonNullable<Preview['aiming']>): Promise<void> {
    while (aiming.pending) {
      const p = aiming.pending;
      aiming.pending = null;
      const name = this.state.status?.targets[aiming.index]?.name;
      if (name) await this.state.ask({ type: 'aim', target: name, point: [p.x, p.y, p.z] });
    }
  }

  /// Letting go hands the target back to the show, after the last aim.
  private endAim(event: PointerEvent): void {
    const aiming = this.aiming;
    if (!aiming) return;
    this.aiming = null;
    if (this.controls) this.controls.enabled = true;
    this.canvas.releasePointerCapture(event.pointerId);
    const name = this.state.status?.targets[aiming.index]?.name;
    void (aiming.sending ?? Promise.resolve()).then(() => {
      if (name) void this.state.ask({ type: 'release_aim', target: name });
    });
  }

  /// Where a point of a URDF link (metres, its frame) is drawn, in the canvas's CSS pixels.
  linkScreenPosition(link: string, point: [number, number, number] = [0, 0, 0]): { x: number; y: number } | null {
    const frame = this.linkFrames.get(link);
    if (!frame) return null;
    this.scene.updateMatrixWorld();
    const p = frame.localToWorld(new THREE.Vector3(...point)).project(this.camera);
    return { x: ((p.x + 1) / 2) * this.canvas.clientWidth, y: ((1 - p.y) / 2) * this.canvas.clientHeight };
  }

  /// Where a target is drawn, in the canvas's CSS pixels.
  targetScreenPosition(index: number): { x: number; y: number } | null {
    const ball = this.targets[index];
    if (!ball) return null;
    const p = ball.getWorldPosition(new THREE.Vector3()).project(this.camera);
    return { x: ((p.x + 1) / 2) * this.canvas.clientWidth, y: ((1 - p.y) / 2) * this.canvas.clientHeight };
  }

  private pick(event: MouseEvent): void {
    const ray = this.ray(event);
    const hit = ray.intersectObjects(this.joints.map((j) => j.ball))[0];
    const index = hit?.object.userData.joint as number | undefined;
    const channel = index === undefined ? null : this.joints[index]?.joint.channel;
    if (!channel) return;
    this.state.channel = channel;
    this.state.changed();
  }

  render(): void {
    const kinematics = this.state.rig?.kinematics ?? null;
    const usable = kinematics !== null && this.renderer !== null;
    this.canvas.hidden = !usable;
    if (usable && this.built !== kinematics) this.build(kinematics);
    put(this.message, 'hidden', usable && this.visualProblems.length === 0);
    if (!this.renderer) put(this.message, 'textContent', 'no 3-D preview: this browser gives no WebGL');
    else if (!kinematics) put(this.message, 'textContent', 'this rig has no kinematics section: the gauges below show every channel');
    else if (this.visualProblems.length > 0)
      put(this.message, 'textContent', `drawn with simple shapes as well: ${this.visualProblems.join('; ')}`);
    if (!usable) return;
    for (const view of this.joints) {
      const q = this.jointValue(view.joint.name) ?? 0;
      const axis = new THREE.Vector3(...view.joint.axis);
      if (view.joint.type === 'revolute') view.motion.quaternion.setFromAxisAngle(axis, q);
      else if (view.joint.type === 'prismatic') view.motion.position.copy(axis.multiplyScalar(q));
      view.ball.material = view.joint.channel !== null && view.joint.channel === this.state.channel ? this.selectedMaterial : this.jointMaterial;
    }
    // The show's targets where the status says they are.
    const targets = this.state.status?.targets ?? [];
    const framed = this.targets.length;
    while (this.targets.length < targets.length && this.figure) {
      const ball = new THREE.Mesh(new THREE.SphereGeometry(this.targetRadius, 20, 14), this.targetMaterial);
      ball.userData.target = this.targets.length;
      this.figure.add(ball);
      this.targets.push(ball);
      const line = new THREE.Line(new THREE.BufferGeometry(), this.sightMaterial);
      this.scene.add(line);
      this.sightLines.push(line);
    }
    this.targets.forEach((ball, i) => {
      const target = targets[i];
      ball.visible = target !== undefined;
      if (!target) return;
      ball.position.set(...target.point);
      ball.material = target.held ? this.heldMaterial : this.targetMaterial;
    });
    this.sightLines.forEach((line, i) => {
      const target = targets[i];
      const from = target ? this.effectors.find((e) => e.name === target.name)?.frame : undefined;
      const ball = this.targets[i];
      line.visible = from !== undefined && ball !== undefined && ball.visible;
      if (!line.visible || !from || !ball) return;
      this.scene.updateMatrixWorld();
      line.geometry.setFromPoints([from.getWorldPosition(new THREE.Vector3()), ball.getWorldPosition(new THREE.Vector3())]);
      line.computeLineDistances();
    });
    // The first time targets appear, the view takes them in.
    if (framed === 0 && this.targets.length > 0) this.frame();
    this.draw();
  }

  private draw(): void {
    if (!this.renderer || this.canvas.hidden) return;
    const width = this.canvas.clientWidth;
    const height = this.canvas.clientHeight;
    if (width === 0 || height === 0) return;
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.renderer.render(this.scene, this.camera);
  }
}
