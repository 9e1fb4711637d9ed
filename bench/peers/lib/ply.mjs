// A small PLY reader for what ReamSim writes (modules/mesh/src/io/PlyIO.cpp: binary little endian by
// default, ASCII on request; `element vertex` with double x/y/z, `element face` with a `list uchar int`).
// It also reads other numeric types, big endian and extra properties, and fans polygons into triangles.
// Returns { positions: Float64Array (x,y,z per vertex), triangles: Uint32Array (3 indices per triangle) }.
import { readFileSync } from 'node:fs';

const SIZES = {
  char: 1, int8: 1, uchar: 1, uint8: 1, short: 2, int16: 2, ushort: 2, uint16: 2,
  int: 4, int32: 4, uint: 4, uint32: 4, float: 4, float32: 4, double: 8, float64: 8,
};

function reader(view, type, little) {
  switch (type) {
    case 'char': case 'int8': return (o) => view.getInt8(o);
    case 'uchar': case 'uint8': return (o) => view.getUint8(o);
    case 'short': case 'int16': return (o) => view.getInt16(o, little);
    case 'ushort': case 'uint16': return (o) => view.getUint16(o, little);
    case 'int': case 'int32': return (o) => view.getInt32(o, little);
    case 'uint': case 'uint32': return (o) => view.getUint32(o, little);
    case 'float': case 'float32': return (o) => view.getFloat32(o, little);
    case 'double': case 'float64': return (o) => view.getFloat64(o, little);
    default: throw new Error(`PLY: unknown property type '${type}'`);
  }
}

function parseHeader(buf, path) {
  const end = buf.indexOf('end_header');
  if (buf.subarray(0, 3).toString('latin1') !== 'ply' || end < 0) throw new Error(`${path}: not a PLY file`);
  let offset = end + 'end_header'.length;
  if (buf[offset] === 0x0d) offset++;
  if (buf[offset] === 0x0a) offset++;
  const lines = buf.subarray(0, end).toString('latin1').split(/\r?\n/);
  let format = null;
  const elements = [];
  for (const raw of lines) {
    const w = raw.trim().split(/\s+/);
    if (w[0] === 'format') format = w[1];
    else if (w[0] === 'element') elements.push({ name: w[1], count: Number(w[2]), props: [] });
    else if (w[0] === 'property') {
      const el = elements[elements.length - 1];
      if (!el) throw new Error(`${path}: property before any element`);
      if (w[1] === 'list') el.props.push({ list: true, countType: w[2], type: w[3], name: w[4] });
      else el.props.push({ list: false, type: w[1], name: w[2] });
    }
  }
  if (!['ascii', 'binary_little_endian', 'binary_big_endian'].includes(format))
    throw new Error(`${path}: unknown PLY format '${format}'`);
  return { format, elements, offset };
}

export function readPly(path) {
  const buf = readFileSync(path);
  const { format, elements, offset } = parseHeader(buf, path);
  const vertexEl = elements.find((e) => e.name === 'vertex');
  const faceEl = elements.find((e) => e.name === 'face');
  if (!vertexEl || !faceEl) throw new Error(`${path}: PLY without vertex or face element`);
  const positions = new Float64Array(vertexEl.count * 3);
  const tris = [];
  const axis = { x: 0, y: 1, z: 2 };
  const faceProp = faceEl.props.findIndex((p) => p.list && (p.name === 'vertex_indices' || p.name === 'vertex_index'));
  if (faceProp < 0) throw new Error(`${path}: PLY face element without vertex_indices`);
  const addPolygon = (poly) => {
    for (let k = 1; k + 1 < poly.length; ++k) tris.push(poly[0], poly[k], poly[k + 1]);
  };

  if (format === 'ascii') {
    const tokens = buf.subarray(offset).toString('latin1').split(/\s+/).filter((t) => t.length > 0);
    let t = 0;
    for (const el of elements) {
      for (let i = 0; i < el.count; ++i) {
        for (let p = 0; p < el.props.length; ++p) {
          const prop = el.props[p];
          if (prop.list) {
            const n = Number(tokens[t++]);
            const values = tokens.slice(t, t + n).map(Number);
            t += n;
            if (el === faceEl && p === faceProp) addPolygon(values);
          } else {
            const v = Number(tokens[t++]);
            if (el === vertexEl && prop.name in axis) positions[i * 3 + axis[prop.name]] = v;
          }
        }
      }
    }
  } else {
    const little = format === 'binary_little_endian';
    const view = new DataView(buf.buffer, buf.byteOffset, buf.byteLength);
    let o = offset;
    for (const el of elements) {
      const props = el.props.map((p) => ({
        ...p,
        read: reader(view, p.type, little),
        size: SIZES[p.type],
        readCount: p.list ? reader(view, p.countType, little) : null,
        countSize: p.list ? SIZES[p.countType] : 0,
      }));
      for (let i = 0; i < el.count; ++i) {
        for (let p = 0; p < props.length; ++p) {
          const prop = props[p];
          if (prop.list) {
            const n = prop.readCount(o);
            o += prop.countSize;
            if (el === faceEl && p === faceProp) {
              const poly = new Array(n);
              for (let k = 0; k < n; ++k) poly[k] = prop.read(o + k * prop.size);
              addPolygon(poly);
            }
            o += n * prop.size;
          } else {
            if (el === vertexEl && prop.name in axis) positions[i * 3 + axis[prop.name]] = prop.read(o);
            o += prop.size;
          }
        }
      }
    }
    if (o > buf.length) throw new Error(`${path}: PLY truncated`);
  }
  const triangles = Uint32Array.from(tris);
  for (const v of triangles) if (v >= vertexEl.count) throw new Error(`${path}: vertex index ${v} out of range`);
  return { positions, triangles };
}

// Edge counts of an indexed triangle mesh: directed edges without their opposite (open border) and
// undirected edges used by more than two triangles. Informational: what the peers are given.
export function edgeReport(mesh) {
  const n = mesh.positions.length / 3;
  const directed = new Map();
  const t = mesh.triangles;
  for (let f = 0; f < t.length; f += 3)
    for (let k = 0; k < 3; ++k) {
      const a = t[f + k], b = t[f + ((k + 1) % 3)];
      const key = a * n + b;
      directed.set(key, (directed.get(key) || 0) + 1);
    }
  let border = 0, nonManifold = 0, inconsistent = 0;
  for (const [key, count] of directed) {
    const a = Math.floor(key / n), b = key - a * n;
    const back = directed.get(b * n + a) || 0;
    if (back === 0) border += count;
    if (count > 1) inconsistent += 1;  // the same directed edge twice: inconsistent orientation or > 2 faces
    if (a < b && count + back > 2) nonManifold += 1;
  }
  return { border_edges: border, non_manifold_edges: nonManifold, repeated_directed_edges: inconsistent };
}

// Row-major 4x4 applied to points.
export function transformPositions(positions, m) {
  const out = new Float64Array(positions.length);
  for (let i = 0; i < positions.length; i += 3) {
    const x = positions[i], y = positions[i + 1], z = positions[i + 2];
    out[i] = m[0] * x + m[1] * y + m[2] * z + m[3];
    out[i + 1] = m[4] * x + m[5] * y + m[6] * z + m[7];
    out[i + 2] = m[8] * x + m[9] * y + m[10] * z + m[11];
  }
  return out;
}

export function readSequence(dir) {
  const bone = readPly(`${dir}/bone.ply`);
  const tool = readPly(`${dir}/tool.ply`);
  const seq = JSON.parse(readFileSync(`${dir}/steps.json`, 'utf8'));
  const steps = seq.steps;
  if (!Array.isArray(steps) || steps.some((m) => !Array.isArray(m) || m.length !== 16))
    throw new Error(`${dir}/steps.json: 'steps' must be a list of row-major 4x4 matrices (16 numbers)`);
  return { bone, tool, steps };
}
