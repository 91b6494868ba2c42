// CommonJS users: require('meshq-wasm') has the same typings, without init (web/tests/types.mjs).
import meshq = require('meshq-wasm');

export function fromRequire(positions: Float32Array): number {
  const bvh = meshq.MeshBvh.build(positions, null, { quality: 'high' });
  const hit = bvh.raycast([0, 0, 1], [0, 0, -1]);
  // @ts-expect-error the ray parameter is a number
  const wrong: string | undefined = hit?.t;
  return (hit?.t ?? 0) + (wrong?.length ?? 0);
}
