// A URDF figure's looks in the 3-D preview: its links' boxes, cylinders, spheres and meshes (STL,
// Collada and OBJ files the studio serves from the rig's URDF folder), each in its link's frame.
// Meshes load in the background; one that cannot be had is reported, and the preview then also
// draws the joint tree's simple shapes so that no part of the figure goes missing.
import * as THREE from 'three';
import { ColladaLoader } from 'three/examples/jsm/loaders/ColladaLoader.js';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import type { Transform, Visual } from './protocol';

export function placed(transform: Transform): THREE.Group {
  const group = new THREE.Group();
  const [x, y, z] = transform.xyz;
  const [w, qx, qy, qz] = transform.quaternion;
  group.position.set(x, y, z);
  group.quaternion.set(qx, qy, qz, w);
  return group;
}

/// The studio's URL for a mesh, with the token the page was opened with.
function meshUrl(url: string): string {
  const token = new URLSearchParams(location.search).get('token');
  return token ? `${url}?token=${encodeURIComponent(token)}` : url;
}

function materialFor(visual: Visual): THREE.MeshStandardMaterial {
  const [r, g, b, a] = visual.color ?? [0.72, 0.75, 0.8, 1];
  return new THREE.MeshStandardMaterial({
    color: new THREE.Color(r, g, b),
    opacity: a,
    transparent: a < 1,
    metalness: 0.1,
    roughness: 0.7,
    side: THREE.DoubleSide,
  });
}

/// Loads a mesh file into an object; rejects with the reason.
async function loadMesh(visual: Visual, material: THREE.Material): Promise<THREE.Object3D> {
  const url = meshUrl(visual.url ?? '');
  switch (visual.format) {
    case 'stl': {
      const geometry = await new STLLoader().loadAsync(url);
      geometry.computeVertexNormals();
      return new THREE.Mesh(geometry, material);
    }
    case 'obj': {
      const object = await new OBJLoader().loadAsync(url);
      object.traverse((child) => {
        if (child instanceof THREE.Mesh) {
          child.geometry.computeVertexNormals();
          child.material = material;
        }
      });
      return object;
    }
    case 'dae': {
      // Collada carries its own materials and unit; its scene is placed as the file says.
      const collada = await new ColladaLoader().loadAsync(url);
      if (!collada) throw new Error('not a Collada document');
      return collada.scene;
    }
    default:
      throw new Error(`cannot draw ${visual.file ?? 'a mesh'}: its format is not STL, Collada (.dae) or OBJ`);
  }
}

function primitive(visual: Visual, material: THREE.Material): THREE.Object3D {
  switch (visual.shape) {
    case 'box': {
      const [x, y, z] = visual.size ?? [0, 0, 0];
      return new THREE.Mesh(new THREE.BoxGeometry(x, y, z), material);
    }
    case 'sphere':
      return new THREE.Mesh(new THREE.SphereGeometry(visual.radius ?? 0, 24, 16), material);
    default: {
      // three.js draws a cylinder along y; a URDF cylinder lies along its frame's z.
      const radius = visual.radius ?? 0;
      const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, visual.length ?? 0, 24), material);
      mesh.rotation.x = Math.PI / 2;
      return mesh;
    }
  }
}

export interface VisualsLoad {
  /// Every visual added to the figure (meshes once loaded).
  objects: THREE.Object3D[];
  /// Settles when every mesh has loaded or failed; the failures' reasons, one per mesh.
  done: Promise<string[]>;
}

/// Adds each visual to the frame `frameOf(visual.joint)` gives (the joint's moving frame, or the
/// figure's base frame for null). `loaded` is called as each mesh arrives (to redraw).
export function addVisuals(visuals: Visual[], frameOf: (joint: number | null) => THREE.Object3D, loaded: () => void): VisualsLoad {
  const objects: THREE.Object3D[] = [];
  const pending: Promise<string | null>[] = [];
  const named = (visual: Visual): string => `${visual.file ?? 'a mesh'} of link ${visual.link}`;
  for (const visual of visuals) {
    const frame = placed(visual.origin);
    frameOf(visual.joint).add(frame);
    const material = materialFor(visual);
    if (visual.shape !== 'mesh') {
      const object = primitive(visual, material);
      frame.add(object);
      objects.push(object);
      continue;
    }
    if (!visual.found) {
      pending.push(Promise.resolve(`${named(visual)}: not found on the studio's machine`));
      continue;
    }
    const [sx, sy, sz] = visual.scale ?? [1, 1, 1];
    frame.scale.set(sx, sy, sz);
    pending.push(
      loadMesh(visual, material).then(
        (object) => {
          frame.add(object);
          objects.push(object);
          loaded();
          return null;
        },
        (error: unknown) => `${named(visual)}: ${error instanceof Error ? error.message : String(error)}`,
      ),
    );
  }
  return { objects, done: Promise.all(pending).then((reasons) => reasons.filter((r): r is string => r !== null)) };
}
