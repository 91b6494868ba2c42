// Assembles the npm package `meshq-wasm` in wasm/pkg from wasm-pack's two outputs:
//
//   web/   the ES module for browsers and bundlers (wasm/pkg-web), `await init()` first;
//   node/  the CommonJS module for Node (wasm/pkg-nodejs), with an ES-module entry whose
//          `init()` resolves at once, so the same `import init, { MeshBvh } from 'meshq-wasm'`
//          code runs in both;
//
// each with the three.js drop-in, and one package.json whose conditional `exports` pick the
// right one (`meshq-wasm`, `meshq-wasm/three`). The typings are wasm-bindgen's, with one fix:
// it writes optional parameters (Rust `Option`s, typed `… | null` here) as required ones, so
// trailing parameters whose type admits `null` are marked optional (`near?: number | null`).
//
// Usage: node wasm/js/assemble.mjs <crate version>
import { cpSync, existsSync, mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const wasmDir = join(dirname(fileURLToPath(import.meta.url)), '..');
const out = join(wasmDir, 'pkg');
const version = process.argv[2];
if (!/^\d+\.\d+\.\d+/.test(version ?? '')) throw new Error(`usage: assemble.mjs <version>, got ${version}`);

/** Marks trailing parameters whose type admits `null` optional, in every signature. */
export function optionalTrailing(dts) {
  return dts.replace(/^(\s*(?:static\s+)?(?:export function\s+)?[A-Za-z_$][\w$]*\s*\()(.*)(\)\s*:[^;{]*;)$/gm, (line, head, params, tail) => {
    const parts = splitParams(params);
    for (let i = parts.length - 1; i >= 0; i--) {
      const m = /^(\s*[A-Za-z_$][\w$]*)(\??):\s*(.*)$/s.exec(parts[i]);
      if (!m || !/\bnull\b/.test(m[3])) break;
      parts[i] = `${m[1]}?: ${m[3]}`;
    }
    return head + parts.join(',') + tail;
  });
}

/** Splits a parameter list at top-level commas (not inside `<>`, `{}`, `()` or `[]`). */
function splitParams(params) {
  const parts = [];
  let depth = 0;
  let start = 0;
  for (let i = 0; i < params.length; i++) {
    const c = params[i];
    if ('<{(['.includes(c)) depth++;
    else if ('>})]'.includes(c) && params[i - 1] !== '=') depth--;
    else if (c === ',' && depth === 0) {
      parts.push(params.slice(start, i));
      start = i + 1;
    }
  }
  if (params.trim() !== '') parts.push(params.slice(start));
  return parts;
}

/** wasm-bindgen's inline JavaScript snippets are ES modules even in the CommonJS build, which
 *  `require`s them; written as CommonJS here, they load in every Node version. Only `export
 *  function` declarations are expected (the crate's own snippets). */
export function snippetAsCommonJs(source, file) {
  const names = [];
  const body = source.replace(/^export function ([A-Za-z_$][\w$]*)\s*\(/gm, (_, name) => {
    names.push(name);
    return `function ${name}(`;
  });
  if (/^\s*(export|import)\b/m.test(body)) throw new Error(`${file}: only export function declarations can be converted`);
  return `'use strict';\n${body}\nmodule.exports = { ${names.join(', ')} };\n`;
}

/** The files of a folder and its subfolders. */
function filesUnder(dir) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) =>
    e.isDirectory() ? filesUnder(join(dir, e.name)) : [join(dir, e.name)]);
}

/** Copies wasm-pack's output `from` into `to`, typings fixed, its own package.json dropped. */
function copyOutput(from, to, type) {
  mkdirSync(to, { recursive: true });
  for (const name of ['meshq_wasm.js', 'meshq_wasm_bg.wasm', 'meshq_wasm_bg.wasm.d.ts', 'snippets']) {
    if (existsSync(join(from, name))) cpSync(join(from, name), join(to, name), { recursive: true });
  }
  if (type === 'commonjs' && existsSync(join(to, 'snippets'))) {
    for (const file of filesUnder(join(to, 'snippets')).filter((f) => f.endsWith('.js'))) {
      writeFileSync(file, snippetAsCommonJs(readFileSync(file, 'utf8'), file));
    }
  }
  let dts = optionalTrailing(readFileSync(join(from, 'meshq_wasm.d.ts'), 'utf8'));
  // wasm-bindgen declares `[Symbol.dispose]()`: name the library that types it, so the
  // typings compile whatever `lib` the user's project sets.
  if (dts.includes('Symbol.dispose')) dts = `/// <reference lib="esnext.disposable" />\n${dts}`;
  writeFileSync(join(to, 'meshq_wasm.d.ts'), dts);
  // Each folder says how Node reads its .js files.
  writeFileSync(join(to, 'package.json'), `${JSON.stringify({ type }, null, 2)}\n`);
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  rmSync(out, { recursive: true, force: true });
  copyOutput(join(wasmDir, 'pkg-web'), join(out, 'web'), 'module');
  copyOutput(join(wasmDir, 'pkg-nodejs'), join(out, 'node'), 'commonjs');

  const js = join(wasmDir, 'js');
  const dropin = readFileSync(join(js, 'three.js'), 'utf8');
  const dropinTypes = readFileSync(join(js, 'three.d.ts'), 'utf8');
  writeFileSync(join(out, 'web', 'three.js'), dropin);
  writeFileSync(join(out, 'web', 'three.d.ts'), dropinTypes);
  writeFileSync(join(out, 'node', 'three.mjs'), dropin);
  writeFileSync(join(out, 'node', 'three.d.mts'), dropinTypes);
  const augment = readFileSync(join(js, 'three-augment.d.ts'), 'utf8');
  const augmentJs = readFileSync(join(js, 'three-augment.js'), 'utf8');
  writeFileSync(join(out, 'web', 'three-augment.d.ts'), augment);
  writeFileSync(join(out, 'web', 'three-augment.js'), augmentJs);
  writeFileSync(join(out, 'node', 'three-augment.d.mts'), augment.replace("from './three.js'", "from './three.mjs'"));
  writeFileSync(join(out, 'node', 'three-augment.mjs'), augmentJs);
  cpSync(join(js, 'node-entry.mjs'), join(out, 'node', 'index.mjs'));
  // The worker pool: one source, and a worker body behind a prologue per environment.
  const pool = readFileSync(join(js, 'pool.js'), 'utf8');
  const poolTypes = readFileSync(join(js, 'pool.d.ts'), 'utf8');
  const body = readFileSync(join(js, 'pool-worker-body.js'), 'utf8');
  writeFileSync(join(out, 'web', 'pool.js'), pool);
  writeFileSync(join(out, 'web', 'pool.d.ts'), poolTypes);
  writeFileSync(join(out, 'node', 'pool.mjs'), pool);
  writeFileSync(join(out, 'node', 'pool.d.mts'), poolTypes);
  writeFileSync(join(out, 'web', 'pool-worker.js'), `// meshq-wasm/pool's worker, browser build.
import init, { MeshBvh } from './meshq_wasm.js';
const ready = init();
const post = (message, transfer) => self.postMessage(message, transfer);
self.onmessage = (event) => handle(event.data);

${body}`);
  writeFileSync(join(out, 'node', 'pool-worker.mjs'), `// meshq-wasm/pool's worker, Node build.
import { parentPort } from 'node:worker_threads';
import { MeshBvh } from './meshq_wasm.js';
const ready = Promise.resolve();
const post = (message, transfer) => parentPort.postMessage(message, transfer);
parentPort.on('message', (message) => handle(message));

${body}`);
  cpSync(join(js, 'node-entry.d.mts'), join(out, 'node', 'index.d.mts'));
  cpSync(join(js, 'README.md'), join(out, 'README.md'));

  const three = {
    node: { types: './node/three.d.mts', default: './node/three.mjs' },
    types: './web/three.d.ts',
    default: './web/three.js',
  };
  const pkg = {
    name: 'meshq-wasm',
    version,
    description: 'Ray casts, closest points and overlaps on triangle meshes in WebAssembly, with a three.js drop-in for three-mesh-bvh users; prebuilt blobs load without a rebuild',
    license: 'MIT OR Apache-2.0',
    keywords: ['bvh', 'raycast', 'three.js', 'three-mesh-bvh', 'webassembly', 'collision', 'closest-point'],
    type: 'module',
    exports: {
      '.': {
        node: {
          import: { types: './node/index.d.mts', default: './node/index.mjs' },
          require: { types: './node/meshq_wasm.d.ts', default: './node/meshq_wasm.js' },
        },
        types: './web/meshq_wasm.d.ts',
        default: './web/meshq_wasm.js',
      },
      './three': three,
      './three.js': three,
      './pool': {
        node: { types: './node/pool.d.mts', default: './node/pool.mjs' },
        types: './web/pool.d.ts',
        default: './web/pool.js',
      },
      './three-augment': {
        node: { types: './node/three-augment.d.mts', default: './node/three-augment.mjs' },
        types: './web/three-augment.d.ts',
        default: './web/three-augment.js',
      },
      './package.json': './package.json',
    },
    main: './node/meshq_wasm.js',
    module: './web/meshq_wasm.js',
    types: './web/meshq_wasm.d.ts',
    files: ['web/', 'node/', 'README.md'],
    // The drop-in adds three-mesh-bvh's methods to MeshBvh when imported; wasm-bindgen's
    // snippets are imported for their exports only.
    sideEffects: ['./web/three.js', './node/three.mjs'],
    peerDependencies: { three: '>=0.159.0' },
    peerDependenciesMeta: { three: { optional: true } },
    engines: { node: '>=18' },
  };
  writeFileSync(join(out, 'package.json'), `${JSON.stringify(pkg, null, 2)}\n`);
}
