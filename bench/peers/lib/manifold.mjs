// Peer: manifold-3d (the official WASM build of Manifold). Manifold's JS Mesh holds float32 positions,
// so the bone and the tool are built from float32 and then given back their double coordinates with
// warpBatch (a vertex is matched by its float32 rounding; if two vertices round alike the float32 copy
// stays and `coordinates` says so). The tool Manifold is built once; each step is
// tool.transform(M) subtracted from the bone, the Boolean forced by numTri() (Manifold's Booleans are
// lazy), all inside the timed region.
import Module from 'manifold-3d';
import { readFileSync } from 'node:fs';

// manifold-3d's "exports" hide package.json; it sits beside manifold.js.
const manifest = new URL('package.json', import.meta.resolve('manifold-3d'));
export const packageName = `manifold-3d@${JSON.parse(readFileSync(manifest, 'utf8')).version}`;
export const algorithm = 'Manifold: exact-topology mesh Booleans (symbolic perturbation), double precision inside';

let wasm = null;

function restoreDoubles(manifold, positions) {
  const exact = new Map();
  const f = new Float32Array(3);
  const key = () => `${f[0]},${f[1]},${f[2]}`;
  let ambiguous = 0;
  for (let i = 0; i < positions.length; i += 3) {
    f[0] = positions[i]; f[1] = positions[i + 1]; f[2] = positions[i + 2];
    const k = key();
    if (exact.has(k)) ++ambiguous;
    exact.set(k, i);
  }
  if (ambiguous > 0) return { manifold, coordinates: `float32 (${ambiguous} vertices round to the same float32 point)` };
  let missing = 0;
  const warped = manifold.warpBatch((v, n) => {
    for (let j = 0; j < 3 * n; j += 3) {
      f[0] = v[j]; f[1] = v[j + 1]; f[2] = v[j + 2];
      const i = exact.get(key());
      if (i === undefined) { ++missing; continue; }
      v[j] = positions[i]; v[j + 1] = positions[i + 1]; v[j + 2] = positions[i + 2];
    }
  });
  manifold.delete();
  return { manifold: warped, coordinates: missing === 0 ? 'double' : `double except ${missing} vertices (float32)` };
}

function build(mesh, what) {
  const { Manifold, Mesh } = wasm;
  const m = new Mesh({
    numProp: 3,
    vertProperties: Float32Array.from(mesh.positions),
    triVerts: Uint32Array.from(mesh.triangles),
  });
  try {
    return restoreDoubles(new Manifold(m), mesh.positions);
  } catch (e) {
    // ManifoldError: code is the ErrorStatus ('NotManifold', 'NonFiniteVertex', ...).
    const err = new Error(`${what}: manifold-3d refused it: ${e.code || 'error'} (${e.message || e})`);
    err.refusal = true;
    throw err;
  }
}

export async function create(bone, tool) {
  if (!wasm) {
    wasm = await Module();
    wasm.setup();
  }
  const b = build(bone, 'bone');
  const t = build(tool, 'tool');
  let current = b.manifold;
  return {
    coordinates: { bone: b.coordinates, tool: t.coordinates },
    checks: 'oriented 2-manifold and finite vertices at construction (self-intersections are not checked)',
    faces: () => current.numTri(),
    volume: () => current.volume(),
    step(m) {
      // steps.json is row-major; Manifold's Mat4 is column-major.
      const colMajor = [m[0], m[4], m[8], m[12], m[1], m[5], m[9], m[13], m[2], m[6], m[10], m[14], m[3], m[7], m[11], m[15]];
      const t0 = performance.now();
      const placed = t.manifold.transform(colMajor);
      const next = current.subtract(placed);
      const faces = next.numTri();  // forces the lazy Boolean
      const ms = performance.now() - t0;
      const status = next.status();
      placed.delete();
      current.delete();
      current = next;
      if (status !== 'NoError') throw new Error(`manifold-3d status ${status} after the subtraction`);
      return { ms, faces };
    },
    end: () => ({ faces: current.numTri(), volume: current.volume() }),
  };
}
