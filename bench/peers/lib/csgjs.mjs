// Peer: csg.js, Evan Wallace's BSP-tree CSG (npm package `csg`, the original csg.js source), the
// method of the thesis. Each subtraction builds BSP trees of the whole bone and of the tool from their
// polygons, clips them against each other and returns polygons (convex, split by the BSP planes; not
// welded, T-junctions left). csg.js checks nothing: an open or self-intersecting input is processed as
// if it bounded a solid (each polygon's plane taken as a half-space boundary), and the result is whatever
// the clipping gives. Faces are counted as triangles (fan of each convex polygon), as the thesis counts.
import { createRequire } from 'node:module';
import { transformPositions } from './ply.mjs';

const require = createRequire(import.meta.url);
const CSG = require('csg');
export const packageName = `csg@${require('csg/package.json').version}`;
export const algorithm = "csg.js (Evan Wallace): BSP trees of both solids rebuilt per operation, polygon clipping with EPSILON " +
  `${CSG.Plane.EPSILON}`;

function polygons(positions, triangles) {
  const verts = new Array(positions.length / 3);
  for (let i = 0; i < verts.length; ++i)
    verts[i] = new CSG.Vector(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
  const out = [];
  const zero = new CSG.Vector(0, 0, 0);
  for (let f = 0; f < triangles.length; f += 3)
    out.push(new CSG.Polygon([
      new CSG.Vertex(verts[triangles[f]], zero),
      new CSG.Vertex(verts[triangles[f + 1]], zero),
      new CSG.Vertex(verts[triangles[f + 2]], zero),
    ]));
  return CSG.fromPolygons(out);
}

function triangleCount(csg) {
  let n = 0;
  for (const p of csg.polygons) n += p.vertices.length - 2;
  return n;
}

function volume(csg) {
  let six = 0;
  for (const p of csg.polygons) {
    const v = p.vertices, a = v[0].pos;
    for (let k = 1; k + 1 < v.length; ++k) {
      const b = v[k].pos, c = v[k + 1].pos;
      six += a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
    }
  }
  return six / 6;
}

export async function create(bone, tool) {
  let current = polygons(bone.positions, bone.triangles);
  return {
    coordinates: { bone: 'double', tool: 'double' },
    checks: 'none (csg.js accepts any polygon soup)',
    faces: () => triangleCount(current),
    volume: () => volume(current),
    step(m) {
      const c0 = performance.now();
      const placed = polygons(transformPositions(tool.positions, m), tool.triangles);
      const convertMs = performance.now() - c0;
      const t0 = performance.now();
      current = current.subtract(placed);
      const ms = performance.now() - t0;
      return { ms, convertMs, faces: triangleCount(current), polygons: current.polygons.length };
    },
    end: () => ({ faces: triangleCount(current), polygons: current.polygons.length, volume: volume(current) }),
  };
}
