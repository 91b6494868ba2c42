// The package's TypeScript typings against its run-time API and against the TypeScript
// compiler, using the package as installed in web/node_modules/meshq-wasm (scripts/build-web.sh
// puts it there from the `npm pack` tarball):
// - every function and `MeshBvh` member the typings declare exists at run time with the
//   declared number of parameters, and every one that exists is declared;
// - `tsc --noEmit` compiles web/tests/types/*.ts (every documented call, and calls the typings
//   must refuse) with bundler resolution and with Node's (ES module and CommonJS);
// - with three-mesh-bvh's typings in the same compilation, the drop-in's still compile, while
//   adding 'meshq-wasm/three-augment' is refused (the check can fail).
// Run after scripts/build-web.sh: node web/tests/types.mjs
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { fileURLToPath, pathToFileURL } from 'node:url';
import * as meshq from 'meshq-wasm';

const web = fileURLToPath(new URL('..', import.meta.url));
const require = createRequire(import.meta.url);
const tsc = `${web}/node_modules/.bin/tsc`;

/** Names and parameter counts of a declaration block's methods: `name(a, b?)` → 2. */
function declaredMethods(block) {
  const methods = new Map();
  for (const m of block.matchAll(/^\s*(static\s+)?(?:readonly\s+)?([A-Za-z_$][\w$]*)\s*(\((.*)\)\s*:|:)/gm)) {
    const [, isStatic, name, , params] = m;
    const count = params === undefined || params.trim() === '' ? 0 : params.split(/,(?![^<{(\[]*[>})\]])/).length;
    methods.set(`${isStatic ? 'static ' : ''}${name}`, params === undefined ? 'property' : count);
  }
  return methods;
}

// The browser build runs in Node too, given the .wasm bytes.
const installed = `${web}/node_modules/meshq-wasm`;
const browser = await import(pathToFileURL(`${installed}/web/meshq_wasm.js`).href);
browser.initSync({ module: readFileSync(`${installed}/web/meshq_wasm_bg.wasm`) });
assert.notEqual(browser.MeshBvh, meshq.MeshBvh, 'two builds');

for (const [build, dts, module] of [
  ['web', 'web/meshq_wasm.d.ts', browser],
  ['node', 'node/meshq_wasm.d.ts', require('meshq-wasm')],
  ['node, ES module', 'node/meshq_wasm.d.ts', meshq],
]) {
  const text = readFileSync(`${installed}/${dts}`, 'utf8');
  // Each class's declared methods and statics equal the run-time ones.
  const members = {};
  for (const name of ['MeshBvh', 'geometry']) {
    const classBlock = new RegExp(`export class ${name} \\{([\\s\\S]*?)\\n\\}`).exec(text)[1].replace(/\/\*\*[\s\S]*?\*\//g, '');
    const declared = declaredMethods(classBlock);
    declared.delete('private constructor');
    const runtime = new Map();
    for (const key of Object.getOwnPropertyNames(module[name].prototype)) {
      if (key === 'constructor' || key === '__destroy_into_raw') continue;
      const d = Object.getOwnPropertyDescriptor(module[name].prototype, key);
      runtime.set(key, d.get ? 'property' : d.value.length);
    }
    for (const key of Object.getOwnPropertyNames(module[name])) {
      if (['length', 'name', 'prototype', '__wrap'].includes(key)) continue;
      const d = Object.getOwnPropertyDescriptor(module[name], key);
      runtime.set(`static ${key}`, d.get ? 'property' : d.value.length);
    }
    // `[Symbol.dispose]` is a symbol, not a name; `free` is declared and present.
    assert.deepEqual(new Map([...declared].sort()), new Map([...runtime].sort()), `${build}: ${name} typings = run time`);
    members[name] = declared.size;
  }

  const functions = [...text.matchAll(/^export function ([A-Za-z_$][\w$]*)\s*\((.*)\)\s*:/gm)]
    .map(([, name, params]) => [name, params.trim() === '' ? 0 : params.split(/,(?![^<{(\[]*[>})\]])/).length])
    .filter(([name]) => !['initSync', '__wbg_init'].includes(name));
  for (const [name, count] of functions) {
    assert.equal(typeof module[name], 'function', `${build}: ${name} declared but missing`);
    assert.equal(module[name].length, count, `${build}: ${name} parameters`);
  }
  const exported = Object.keys(module).filter((k) => typeof module[k] === 'function' && !['MeshBvh', 'geometry'].includes(k)
    && !['default', 'initSync'].includes(k));
  assert.deepEqual(exported.sort(), functions.map(([n]) => n).sort(), `${build}: every exported function is declared`);
  console.log(`typings (${build}): ${members.MeshBvh} MeshBvh members, ${members.geometry} geometry members and ${functions.length} functions, as at run time`);
}

function compile(config) {
  try {
    execFileSync(tsc, ['-p', `${web}/tests/types/tsconfig.${config}.json`], { cwd: web, encoding: 'utf8', stdio: 'pipe' });
    return '';
  } catch (e) {
    return `${e.stdout}${e.stderr}` || String(e);
  }
}

for (const config of ['bundler', 'node', 'both']) {
  const errors = compile(config);
  assert.equal(errors, '', `tsc ${config}:\n${errors}`);
  console.log(`tsc --noEmit (${config}): compiles`);
}
const clash = compile('clash');
assert.match(clash, /TS2717: Subsequent property declarations must have the same type.*boundsTree/,
  'three-augment beside three-mesh-bvh is refused');
console.log('tsc --noEmit (clash): three-augment beside three-mesh-bvh refused, as documented');
