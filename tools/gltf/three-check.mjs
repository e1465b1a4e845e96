// Loads a .glb in three.js (npm, pinned in tools/package.json) inside Debian's headless
// chromium, plays its first animation to given times and compares vertices, read with three's
// morph-aware Mesh.getVertexPosition and the node's world matrix, with the positions FaceSketch
// sampled there. Fails if any is further than the tolerance (mm).
//   node tools/gltf/three-check.mjs FILE.glb EXPECTED.json
// EXPECTED.json: {"toleranceMm": 0.01, "mmPerUnit": 1000,
//                 "checks": [{"time": s, "node": "face", "vertex": i, "position": [x, y, z]}, ...]}
// mmPerUnit converts three's world units (glTF metres) back to mm. Works offline: the page and
// three.js are served from this process on 127.0.0.1; the page posts its answer back.
import { spawn } from 'node:child_process';
import { createServer } from 'node:http';
import { mkdir, mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const [glbPath, expectedPath] = process.argv.slice(2);
if (!glbPath || !expectedPath) {
    console.error('usage: node tools/gltf/three-check.mjs FILE.glb EXPECTED.json');
    process.exit(2);
}
const here = path.dirname(fileURLToPath(import.meta.url));
const threeRoot = path.join(here, '..', 'node_modules', 'three');
const expected = JSON.parse(await readFile(expectedPath, 'utf8'));
const chromium = process.env.FACESKETCH_CHROMIUM ?? 'chromium';

const page = `<!doctype html><html><head><meta charset="utf-8">
<script type="importmap">{"imports": {"three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/"}}</script>
</head><body><script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
async function run() {
    const checks = await (await fetch('/expected.json')).json();
    const bytes = await (await fetch('/model.glb')).arrayBuffer();
    const gltf = await new GLTFLoader().parseAsync(bytes, '/');
    const scene = gltf.scene;
    const mixer = new THREE.AnimationMixer(scene);
    mixer.clipAction(gltf.animations[0]).play();
    const answers = [];
    for (const check of checks.checks) {
        mixer.setTime(check.time);
        scene.updateMatrixWorld(true);
        const mesh = scene.getObjectByName(check.node);
        if (!mesh || !mesh.isMesh) throw new Error('no mesh named ' + check.node);
        const p = mesh.getVertexPosition(check.vertex, new THREE.Vector3()).applyMatrix4(mesh.matrixWorld);
        answers.push({ position: [p.x, p.y, p.z], influences: mesh.morphTargetInfluences ? mesh.morphTargetInfluences.length : 0 });
    }
    return { three: THREE.REVISION, clip: gltf.animations[0].name, duration: gltf.animations[0].duration, answers };
}
run().then((r) => fetch('/answer', { method: 'POST', body: JSON.stringify(r) }),
           (e) => fetch('/answer', { method: 'POST', body: JSON.stringify({ error: String(e && e.stack || e) }) }));
</script></body></html>`;

const types = { '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json', '.html': 'text/html' };
let resolveAnswer;
const answer = new Promise((resolve) => { resolveAnswer = resolve; });
const server = createServer(async (req, res) => {
    try {
        const url = new URL(req.url, 'http://127.0.0.1');
        if (req.method === 'POST' && url.pathname === '/answer') {
            let body = '';
            for await (const chunk of req) body += chunk;
            res.end('ok');
            resolveAnswer(JSON.parse(body));
            return;
        }
        let file;
        if (url.pathname === '/' || url.pathname === '/index.html') {
            res.setHeader('Content-Type', 'text/html');
            res.end(page);
            return;
        } else if (url.pathname === '/model.glb') file = glbPath;
        else if (url.pathname === '/expected.json') file = expectedPath;
        else if (url.pathname.startsWith('/three/')) {
            file = path.join(threeRoot, path.normalize(url.pathname.slice('/three/'.length)));
            if (!file.startsWith(threeRoot)) throw new Error('outside three');
        } else {
            res.statusCode = 404;
            res.end();
            return;
        }
        const data = await readFile(file);
        res.setHeader('Content-Type', types[path.extname(file)] ?? 'application/octet-stream');
        res.end(data);
    } catch (e) {
        res.statusCode = 404;
        res.end(String(e));
    }
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const port = server.address().port;
const profile = await mkdtemp(path.join(tmpdir(), 'facesketch-chromium-'));
// Chromium puts its singleton socket folder (org.chromium.Chromium.*) in TMPDIR and, killed, never
// removes it: pointing TMPDIR inside the profile lets the rm below take it too.
const browserTmp = path.join(profile, 'tmp');
await mkdir(browserTmp);
const browser = spawn(chromium, ['--headless=new', '--no-sandbox', '--disable-gpu', '--no-first-run',
    '--disable-extensions', '--disable-background-networking', '--disable-dev-shm-usage', '--mute-audio',
    `--user-data-dir=${profile}`, `http://127.0.0.1:${port}/`],
    { stdio: ['ignore', 'ignore', 'pipe'], env: { ...process.env, TMPDIR: browserTmp } });
const exited = new Promise((resolve) => browser.once('exit', resolve));
exited.then((code) => resolveAnswer({ error: `chromium exited (code ${code}) before answering` }));
let browserLog = '';
browser.stderr.on('data', (d) => { browserLog += d; });
const timeout = new Promise((resolve) => setTimeout(() => resolve({ error: 'no answer from chromium within 90 s' }), 90000));
const result = await Promise.race([answer, timeout]);
browser.kill('SIGKILL');
await exited;
server.close();
// Chromium's helper processes may still be closing files in the profile for a moment.
await rm(profile, { recursive: true, force: true, maxRetries: 10, retryDelay: 200 });

if (result.error) {
    console.error(`three.js in chromium failed: ${result.error}`);
    if (browserLog) console.error(browserLog.slice(-4000));
    process.exit(1);
}
const tolerance = expected.toleranceMm;
const scale = expected.mmPerUnit;
let worst = 0;
let failed = false;
console.log(`three.js r${result.three} in ${chromium}: clip "${result.clip}", ${result.duration} s`);
expected.checks.forEach((check, i) => {
    const got = result.answers[i].position.map((v) => v * scale);
    const error = Math.hypot(got[0] - check.position[0], got[1] - check.position[1], got[2] - check.position[2]);
    worst = Math.max(worst, error);
    const ok = error <= tolerance;
    if (!ok) failed = true;
    console.log(`${ok ? 'ok  ' : 'FAIL'} t=${check.time} s ${check.node} vertex ${check.vertex}: three (${got.map((v) => v.toFixed(5)).join(', ')}) ` +
        `FaceSketch (${check.position.map((v) => v.toFixed(5)).join(', ')}) mm, off by ${error.toExponential(3)} mm`);
});
console.log(`${expected.checks.length} vertices checked, worst ${worst.toExponential(3)} mm, tolerance ${tolerance} mm`);
process.exit(failed ? 1 : 0);
