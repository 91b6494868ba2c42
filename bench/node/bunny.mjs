// The bundled bunny as the Node benchmarks use it: loaded with three's OBJLoader, attributes
// other than positions dropped, vertices merged into an indexed geometry (as an app would).
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { mergeVertices } from 'three/examples/jsm/utils/BufferGeometryUtils.js';

const root = fileURLToPath(new URL('../..', import.meta.url));
const group = new OBJLoader().parse(readFileSync(`${root}/assets/stanford-bunny.obj`, 'utf8'));
const loaded = group.children[0].geometry;
loaded.deleteAttribute('normal');
loaded.deleteAttribute('uv');

/** The indexed `BufferGeometry`. */
export const geometry = mergeVertices(loaded);
/** Its positions (`Float32Array`, 3 per vertex). */
export const positions = geometry.getAttribute('position').array;
/** Its triangle indices. */
export const index = geometry.index.array;
