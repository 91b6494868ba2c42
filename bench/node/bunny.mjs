// The bundled bunny as the Node benchmarks use it (or the OBJ file MESHQ_BENCH_MESH names):
// loaded with three's OBJLoader, attributes other than positions dropped, vertices merged into
// an indexed geometry (as an app would).
import { readFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { mergeVertices } from 'three/examples/jsm/utils/BufferGeometryUtils.js';

const root = fileURLToPath(new URL('../..', import.meta.url));
const file = resolve(process.env.MESHQ_BENCH_MESH ?? `${root}/assets/stanford-bunny.obj`);
const group = new OBJLoader().parse(readFileSync(file, 'utf8'));
const loaded = group.children[0].geometry;
loaded.deleteAttribute('normal');
loaded.deleteAttribute('uv');

/** The indexed `BufferGeometry`. */
export const geometry = mergeVertices(loaded);
/** Its positions (`Float32Array`, 3 per vertex). */
export const positions = geometry.getAttribute('position').array;
/** Its triangle indices. */
export const index = geometry.index.array;
