// Renders fragment shaders in headless Chromium's WebGL2 (SwiftShader) through page.html.
// Usage: node render.mjs JOBS.json
// JOBS.json: {"jobs": [{"frag": "path.frag", "out": "path.png", "width": W, "height": H,
//                        "uniforms": {...}, "ints": {...}}], "info": "renderer.json"}
// Writes each PNG and a JSON beside it (timings, uniforms set); exits 1 if any job fails.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createRequire } from 'node:module';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, 'package.json'));
const { chromium } = require('playwright-core');

const spec = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
const executablePath = process.env.CHROMIUM || '/usr/bin/chromium-headless-shell';
const browser = await chromium.launch({
  executablePath,
  headless: true,
  args: [
    '--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--use-gl=angle',
    '--ignore-gpu-blocklist', '--disable-gpu-watchdog',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
  ],
});
let failed = 0;
try {
  const page = await browser.newPage();
  page.on('console', (m) => { if (m.type() === 'error') console.error('[page]', m.text()); });
  await page.goto(pathToFileURL(path.join(here, 'page.html')).href);
  await page.waitForFunction(() => window.harnessReady === true);
  const info = await page.evaluate(() => window.rendererInfo());
  console.log(`WebGL: ${info.version} | ${info.glsl} | ${info.vendor} | ${info.renderer}`);
  if (spec.info) fs.writeFileSync(spec.info, JSON.stringify(info, null, 2) + '\n');
  for (const job of spec.jobs) {
    const frag = fs.readFileSync(job.frag, 'utf8');
    const t0 = Date.now();
    try {
      const r = await page.evaluate((j) => window.renderJob(j),
        { frag, width: job.width, height: job.height, uniforms: job.uniforms || {}, ints: job.ints || {}, strip: job.strip });
      fs.writeFileSync(job.out, Buffer.from(r.png.split(',')[1], 'base64'));
      const meta = { compileMs: r.compileMs, drawMs: r.drawMs, glError: r.glError, uniformsSet: r.uniformsSet };
      fs.writeFileSync(job.out.replace(/\.png$/, '.json'), JSON.stringify(meta, null, 2) + '\n');
      if (r.glError !== 0) { console.error(`${job.out}: GL error ${r.glError}`); failed++; }
      console.log(`  ${path.basename(path.dirname(job.out))}/${path.basename(job.out)}: compile ${(r.compileMs / 1000).toFixed(1)} s, draw ${(r.drawMs / 1000).toFixed(1)} s (wall ${((Date.now() - t0) / 1000).toFixed(1)} s)`);
    } catch (e) {
      failed++;
      const message = String(e && e.message || e);
      console.error(`${job.frag}: ${message.slice(0, 4000)}`);
      fs.writeFileSync(job.out.replace(/\.png$/, '.error.txt'), message + '\n');
    }
  }
} finally {
  await browser.close();
}
process.exit(failed ? 1 : 0);
