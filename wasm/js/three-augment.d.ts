// `import 'meshq-wasm/three-augment'` (once, anywhere) declares what the meshq three.js drop-in
// adds to three's BufferGeometry. Leave it out while three-mesh-bvh's own typings are in the
// same compilation: they declare these members with three-mesh-bvh's types.
import type { MeshBvh } from './meshq_wasm.js';
import type { BuildOptions } from './three.js';

declare module 'three' {
  interface BufferGeometry {
    /** The tree `computeBoundsTree` built (or a `MeshBvh.fromBlob` assigned), if any. */
    boundsTree?: MeshBvh | null;
    /** Builds `this.boundsTree` from the geometry's position and index arrays. */
    computeBoundsTree(options?: BuildOptions): MeshBvh;
    /** Frees `this.boundsTree`. */
    disposeBoundsTree(): void;
  }
}
