// SPDX-License-Identifier: MIT
// `shapestruct explore` end to end through its JSON API (no browser): every 4xx case answers with a message and
// leaves the server running, the server listens on 127.0.0.1 only, a folder that is not fuzzy output is refused
// at start with the missing file named, --templates adds part labels and clusters, and nothing is written into
// the output folder.
//   node tests/explore/api_test.mjs --cli <shapestruct> --work <scratch folder>
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) => {
  if (a.startsWith('--')) pairs.push([a.slice(2), all[i + 1]]);
  return pairs;
}, []));
const cli = args.cli, work = args.work;
let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}
function run(...argv) {
  const r = spawnSync(cli, argv, { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`shapestruct ${argv.join(' ')} exited ${r.status}:\n${r.stdout}\n${r.stderr}`);
  return r;
}

if (spawnSync(cli, ['explore', '--help'], { encoding: 'utf8' }).status !== 0) {
  console.log('SHAPESTRUCT_SKIP: this shapestruct was built without `explore` (cpp-httplib missing)');
  process.exit(0);
}

fs.rmSync(work, { recursive: true, force: true });
fs.mkdirSync(work, { recursive: true });
run('generate', 'chairs', '12', '-o', path.join(work, 'chairs'), '--seed', '5');
const out = path.join(work, 'fuzzy');
run('fuzzy', path.join(work, 'chairs'), '-o', out, '--quiet');

// A folder that is not fuzzy output is refused at start, naming the missing file.
{
  const bad = path.join(work, 'not-fuzzy');
  fs.mkdirSync(bad);
  fs.copyFileSync(path.join(out, 'collection.json'), path.join(bad, 'collection.json'));
  const r = spawnSync(cli, ['explore', bad, '--port', '0'], { encoding: 'utf8', timeout: 20000 });
  check(r.status === 1 && /fuzzy\.bin/.test(r.stderr), `a folder without fuzzy.bin is refused naming it (exit ${r.status}: ${r.stderr.trim()})`);
}

function listing(dir) {
  const entries = [];
  for (const e of fs.readdirSync(dir, { withFileTypes: true, recursive: true })) {
    const p = path.join(e.path ?? e.parentPath, e.name);
    const s = fs.statSync(p);
    entries.push(`${path.relative(dir, p)} ${s.size} ${s.mtimeMs}`);
  }
  return entries.sort().join('\n');
}
const before = listing(out);

let stderr = '';
/** Starts `shapestruct explore ARGS --port 0` and waits for its serving line: {server, url}. */
async function serve(extra) {
  const server = spawn(cli, ['explore', ...extra, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  server.stderr.on('data', (d) => { stderr += d; });
  const url = await new Promise((resolve, reject) => {
    let stdout = '';
    const timer = setTimeout(() => reject(new Error(`no 'serving' line after 60 s; stderr:\n${stderr}`)), 60000);
    server.stdout.on('data', (d) => {
      stdout += d;
      const m = stdout.match(/serving (http:\/\/127\.0\.0\.1:\d+)\//);
      if (m) { clearTimeout(timer); resolve(m[1]); }
    });
    server.on('exit', (code) => reject(new Error(`explore exited ${code}:\n${stderr}`)));
  });
  return { server, url };
}
async function stop(server) {
  server.kill('SIGTERM');
  await new Promise((resolve) => { if (server.exitCode !== null) resolve(); else server.on('exit', resolve); });
}
async function getJson(url) {
  const r = await fetch(url);
  return { status: r.status, json: await r.json() };
}

const { server, url } = await serve([out]);
try {
  const port = Number(new URL(url).port);

  async function request(method, p, body) {
    const r = await fetch(url + p, { method, body, headers: body ? { 'content-type': 'application/json' } : {} });
    const text = await r.text();
    let json = null;
    try { json = JSON.parse(text); } catch { /* not JSON */ }
    return { status: r.status, json, text };
  }
  async function expectError(method, p, body, status, pattern, what) {
    const r = await request(method, p, body);
    check(r.status === status && r.json && typeof r.json.error === 'string' && pattern.test(r.json.error),
          `${what}: ${r.status} ${r.json ? r.json.error : r.text.slice(0, 80)}`);
  }

  const c = await request('GET', '/api/collection');
  check(c.status === 200 && c.json.shape_count === 12 && c.json.shapes.length === 12, 'collection lists the 12 shapes');
  const K = c.json.shapes[0].samples;
  const region = (shape, samples) => JSON.stringify({ regions: [{ shape, samples }] });

  await expectError('POST', '/api/query', '{"regions": [{"shape": 0, "samples": [1, 2]', 400, /malformed JSON/, 'malformed JSON');
  await expectError('POST', '/api/query', '[1, 2]', 400, /regions/, 'a body without regions');
  await expectError('POST', '/api/query', '{"regions": []}', 400, /empty/, 'no regions');
  await expectError('POST', '/api/query', region(0, []), 400, /empty/, 'an empty region');
  await expectError('POST', '/api/query', region('zero', [1]), 400, /shape/, 'a shape that is not an index');
  await expectError('POST', '/api/query', region(0, [1, 'x']), 400, /not an integer/, 'a sample that is not an integer');
  await expectError('POST', '/api/query', region(12, [1]), 404, /shape 12 is not in the collection/, 'an unknown shape');
  await expectError('POST', '/api/query', region(0, [K]), 404, new RegExp(`sample ${K} is not a sample of shape 0`), 'an unknown point');
  await expectError('POST', '/api/query', region(0, [-1]), 404, /sample -1/, 'a negative point');
  await expectError('POST', '/api/details', region(0, [1]), 400, /shapes/, 'details without shapes');
  await expectError('POST', '/api/details', JSON.stringify({ regions: [{ shape: 0, samples: [1] }], shapes: [40] }), 404,
                    /shape 40/, 'details of an unknown shape');
  await expectError('GET', '/api/shape/99/mesh', undefined, 404, /shape 99/, 'the mesh of an unknown shape');
  await expectError('GET', '/api/shape/abc/variance', undefined, 404, /abc/, 'the variance of a shape that is not an index');
  await expectError('GET', '/api/nothing', undefined, 404, /no such API path/, 'an unknown API path');

  // ... and the server still answers, correctly.
  const q = await request('POST', '/api/query', region(0, [0, 1, 2, 3]));
  check(q.status === 200 && q.json.order.length === 12 && q.json.order[0] === 0 && q.json.distance[0] === 0,
        'after the errors a query still answers (the example first)');
  const d = await request('POST', '/api/details', JSON.stringify({ regions: [{ shape: 0, samples: [0, 1, 2, 3] }], shapes: [0, 5] }));
  check(d.status === 200 && d.json.details.length === 2 && d.json.details[0].transform.length === 12 &&
        d.json.details[0].highlight.length === K, 'details answer a transform and a highlight per shape');
  const m = await request('GET', '/api/shape/3/mesh');
  check(m.status === 200 && m.json.positions.length === 3 * c.json.shapes[3].vertices &&
        m.json.vertex_sample.length === c.json.shapes[3].vertices, 'a mesh with one nearest sample per vertex');
  const v = await request('GET', '/api/shape/3/variance');
  check(v.status === 200 && v.json.values.length === K && Math.max(...v.json.values) === 1, 'variance normalised to a maximum of 1');
  const can = await request('GET', '/api/canonical');
  check(can.status === 200 && can.json.transforms.length === 12, 'a canonical transform per shape');

  // Loopback only: the port does not answer on the machine's other addresses.
  const others = Object.values(os.networkInterfaces()).flat().filter((i) => i && !i.internal && i.family === 'IPv4');
  for (const iface of others) {
    const refused = await new Promise((resolve) => {
      const s = net.connect({ host: iface.address, port, timeout: 3000 });
      s.on('connect', () => { s.destroy(); resolve(false); });
      s.on('error', () => resolve(true));
      s.on('timeout', () => { s.destroy(); resolve(true); });
    });
    check(refused, `not reachable on ${iface.address}:${port}`);
  }
  if (others.length === 0) console.log('(no non-loopback IPv4 address on this machine: the bind check is the serving line)');
} finally {
  await stop(server);
}

// With `shapestruct templates` output: part label names, a template cluster per shape, a part label per face.
{
  const templates = path.join(work, 'templates');
  run('templates', path.join(work, 'chairs'), '-o', templates, '--quiet', '--no-ply', '--no-points');
  const withParts = await serve([out, '--templates', templates]);
  try {
    const c = await getJson(withParts.url + '/api/collection');
    check(c.status === 200 && c.json.label_names.length > 0 && c.json.shapes.every((s) => Number.isInteger(s.cluster)),
          `--templates: label names (${c.json.label_names}) and a cluster for every shape`);
    const m = await getJson(withParts.url + '/api/shape/2/mesh');
    check(m.status === 200 && Array.isArray(m.json.face_labels) && m.json.face_labels.length === m.json.faces.length / 3 &&
          m.json.face_labels.every((l) => l >= 0 && l < c.json.label_names.length),
          '--templates: one part label per face, each naming a part');
  } finally {
    await stop(withParts.server);
  }
  const r = spawnSync(cli, ['explore', out, '--templates', path.join(work, 'no-such-templates'), '--port', '0'],
                      { encoding: 'utf8', timeout: 20000 });
  check(r.status === 2 && /no-such-templates.*templates\.json is missing/.test(r.stderr), `a missing --templates folder is refused (usage error) naming the missing file (exit ${r.status}: ${r.stderr.trim()})`);
}
check(listing(out) === before, 'nothing in the output folder was written or changed');
if (failures > 0) {
  console.log(`${failures} check(s) failed; server stderr:\n${stderr}`);
  process.exit(1);
}
console.log('all API checks passed');
