// Not a user's file: web/tests/types.mjs compiles it with both.ts and expects TypeScript to
// refuse it, which shows that the coexistence check can fail: with 'meshq-wasm/three-augment'
// and three-mesh-bvh in one compilation, BufferGeometry's members are declared twice.
import 'meshq-wasm/three-augment';
