#!/usr/bin/env node
// Runs one npm peer of `reamsim-cli bench cut --peers` on an exported sequence (bone.ply, tool.ply,
// steps.json from `--export-sequence DIR`): the same subtractions in the same order, each timed around the
// Boolean only (performance.now). Prints one JSON object on stdout (see docs/BENCHMARKS.md).
//
//   node run_peer.mjs --peer manifold-3d|csgjs-bsp --sequence DIR
//                     [--max-total-ms 60000] [--max-faces 2000000] [--max-heap-mb 8192] [--steps N]
//
// The peer runs in a worker thread, so a budget can stop it in the middle of a step (csg.js's BSP grows
// without bound): when the total time or the face count passes its budget, the run stops and the JSON
// records how many steps completed and the faces after each. A peer that refuses the input (manifold-3d:
// not an oriented 2-manifold) is recorded as `refused` with its reason. Exit code 0 for a result
// (refusals and budget stops included), 1 when the JSON reports an `error`, 2 for usage errors.
import { Worker, isMainThread, parentPort, workerData } from 'node:worker_threads';
import { fileURLToPath } from 'node:url';

const PEERS = { 'manifold-3d': './lib/manifold.mjs', 'csgjs-bsp': './lib/csgjs.mjs' };

function percentile(values, q) {
  if (values.length === 0) return null;
  const v = [...values].sort((a, b) => a - b);
  return v[Math.min(v.length - 1, Math.floor(q * (v.length - 1) + 0.5))];
}

async function workerMain() {
  const { peer, sequence, maxFaces, steps: stepLimit } = workerData;
  const { readSequence, edgeReport } = await import('./lib/ply.mjs');
  const lib = await import(PEERS[peer]);
  const post = (m) => parentPort.postMessage(m);
  let seq;
  try {
    seq = readSequence(sequence);
  } catch (e) {
    post({ type: 'error', message: `cannot read the sequence: ${e.message}` });
    return;
  }
  const steps = stepLimit > 0 ? seq.steps.slice(0, stepLimit) : seq.steps;
  post({
    type: 'info', package: lib.packageName, algorithm: lib.algorithm, steps: steps.length,
    faces_start: seq.bone.triangles.length / 3, input: { bone: edgeReport(seq.bone), tool: edgeReport(seq.tool) },
  });
  let state;
  const s0 = performance.now();
  try {
    state = await lib.create(seq.bone, seq.tool);
  } catch (e) {
    post({ type: e.refusal ? 'refused' : 'error', message: e.message });
    return;
  }
  post({ type: 'setup', ms: performance.now() - s0, coordinates: state.coordinates, checks: state.checks });
  for (let i = 0; i < steps.length; ++i) {
    let r;
    try {
      r = state.step(steps[i]);
    } catch (e) {
      post({ type: 'error', message: `step ${i + 1}: ${e.message}` });
      return;
    }
    post({ type: 'step', ...r, volume: state.volume() });  // the volume outside the timed region
    if (r.faces > maxFaces) {
      post({ type: 'budget', reason: `face budget: ${r.faces} faces after step ${i + 1} > --max-faces ${maxFaces}` });
      break;
    }
  }
  const end = state.end();
  post({ type: 'end', ...end });
}

function usage(message) {
  process.stderr.write(`run_peer.mjs: ${message}\n` +
    'usage: node run_peer.mjs --peer manifold-3d|csgjs-bsp --sequence DIR [--max-total-ms MS] [--max-faces N] ' +
    '[--max-heap-mb MB] [--steps N]\n');
  process.exit(2);
}

function mainThread() {
  const opts = { 'max-total-ms': 60000, 'max-faces': 2000000, 'max-heap-mb': 8192, steps: 0 };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) {
    const name = argv[i].replace(/^--/, '');
    if (!argv[i].startsWith('--') || i + 1 >= argv.length) usage(`bad argument '${argv[i]}'`);
    if (!['peer', 'sequence', 'max-total-ms', 'max-faces', 'max-heap-mb', 'steps'].includes(name)) usage(`unknown option --${name}`);
    opts[name] = ['peer', 'sequence'].includes(name) ? argv[i + 1] : Number(argv[i + 1]);
  }
  if (!PEERS[opts.peer]) usage(`--peer must be one of ${Object.keys(PEERS).join(', ')}`);
  if (!opts.sequence) usage('--sequence DIR is required');

  const out = { peer: opts.peer, sequence: opts.sequence, budget: { max_total_ms: opts['max-total-ms'], max_faces: opts['max-faces'] } };
  const stepMs = [], convertMs = [], facesPerStep = [];
  let volumeAfterCompleted = null;
  let finished = false;
  const started = performance.now();
  const worker = new Worker(fileURLToPath(import.meta.url), {
    workerData: { peer: opts.peer, sequence: opts.sequence, maxFaces: opts['max-faces'], steps: opts.steps },
    // csg.js recurses once per BSP level, and its trees get deep: give the thread a large stack.
    resourceLimits: { stackSizeMb: 256, maxOldGenerationSizeMb: opts['max-heap-mb'] },
  });
  const finish = (extra) => {
    if (finished) return;
    finished = true;
    clearTimeout(timer);
    Object.assign(out, extra);
    out.steps_completed = stepMs.length;
    out.volume_after_completed_mm3 = volumeAfterCompleted;
    if (stepMs.length > 0) {
      out.median_ms = percentile(stepMs, 0.5);
      out.p95_ms = percentile(stepMs, 0.95);
      out.total_ms = stepMs.reduce((a, b) => a + b, 0);
      out.step_ms = stepMs;
      if (convertMs.length > 0) out.convert_median_ms = percentile(convertMs, 0.5);
      out.faces_per_step = facesPerStep;
    }
    process.stdout.write(JSON.stringify(out) + '\n');
    worker.terminate().then(() => process.exit(out.error ? 1 : 0));
  };
  const timer = setTimeout(() => {
    finish({
      stopped: `time budget: ${opts['max-total-ms']} ms passed during step ${stepMs.length + 1}` +
        ` (${stepMs.length} of ${out.steps} steps completed)`,
      faces_end: facesPerStep.length ? facesPerStep[facesPerStep.length - 1] : out.faces_start,
    });
  }, opts['max-total-ms']);
  worker.on('message', (m) => {
    switch (m.type) {
      case 'info':
        Object.assign(out, { package: m.package, algorithm: m.algorithm, steps: m.steps, faces_start: m.faces_start, input: m.input });
        break;
      case 'setup':
        Object.assign(out, { setup_ms: m.ms, coordinates: m.coordinates, input_checks: m.checks });
        break;
      case 'step':
        stepMs.push(m.ms);
        facesPerStep.push(m.faces);
        volumeAfterCompleted = m.volume;
        if (m.convertMs !== undefined) convertMs.push(m.convertMs);
        break;
      case 'budget':
        out.stopped = m.reason;
        break;
      case 'end':
        // volume_end_mm3 only when every step ran (a budget stop leaves volume_after_completed_mm3).
        finish({
          faces_end: m.faces, ...(m.polygons !== undefined ? { polygons_end: m.polygons } : {}),
          ...(out.stopped ? {} : { volume_end_mm3: m.volume }),
        });
        break;
      case 'refused':
        finish({ refused: m.message });
        break;
      default:
        finish({ error: m.message });
    }
  });
  const during = () => (out.setup_ms === undefined ? 'during setup' : `during step ${stepMs.length + 1}`);
  worker.on('error', (e) => finish({
    error: e.code === 'ERR_WORKER_OUT_OF_MEMORY' ? `out of memory (heap limit ${opts['max-heap-mb']} MB) ${during()}`
      : `${e.name}: ${e.message} ${during()}`,
    faces_end: facesPerStep.length ? facesPerStep[facesPerStep.length - 1] : out.faces_start,
  }));
  worker.on('exit', (code) => finish({ error: `the worker exited (code ${code}) without a result` }));
}

if (isMainThread) mainThread();
else workerMain();
