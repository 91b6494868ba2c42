// Serves the demo on 127.0.0.1 and prints its URL. Port: MESHQ_PORT (default 8173; 0 or a
// taken port: a free one the OS picks). A page asked for with `?isolated` is served
// cross-origin isolated (COOP and COEP headers). MESHQ_CACHE=1: responses may be cached (by
// default none is). GET /__meshq-demo answers "meshq-demo <token>" so a test can check that this server,
// not another one on the same port, is the one answering.
import { createServer } from 'node:http';
import { createReadStream, statSync } from 'node:fs';
import { extname, join, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('.', import.meta.url));
const token = process.env.MESHQ_SERVER_TOKEN ?? 'meshq';
const cacheable = process.env.MESHQ_CACHE === '1';
const types = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.wasm': 'application/wasm',
  '.meshq': 'application/octet-stream',
  '.png': 'image/png',
};

const server = createServer((request, response) => {
  // The request's own path, parsed as a path (never as `//host/…`); a malformed one is a 400,
  // never a crash.
  let path;
  let isolated;
  try {
    const url = new URL(`http://localhost/${request.url.replace(/^\/+/, '')}`);
    path = decodeURIComponent(url.pathname);
    // `?isolated` serves a page cross-origin isolated (SharedArrayBuffer available, so
    // meshq-wasm/pool shares memory with its workers); everything here is same-origin.
    isolated = url.searchParams.has('isolated');
  } catch {
    response.writeHead(400, { 'content-type': 'text/plain' }).end('bad request');
    return;
  }
  if (path === '/__meshq-demo') {
    response.writeHead(200, { 'content-type': 'text/plain' });
    response.end(`meshq-demo ${token}`);
    return;
  }
  const file = normalize(join(root, path.endsWith('/') ? `${path}index.html` : path));
  if (!file.startsWith(root.endsWith(sep) ? root : root + sep)) {
    response.writeHead(403).end();
    return;
  }
  try {
    if (!statSync(file).isFile()) throw new Error('not a file');
  } catch {
    response.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
    return;
  }
  // A worker's script inherits no policy from its page: it states COEP itself, as an isolated
  // page requires (and a page that is not isolated ignores).
  const worker = /worker\.m?js$/.test(file);
  response.writeHead(200, {
    'content-type': types[extname(file)] ?? 'application/octet-stream',
    // MESHQ_CACHE=1 lets the browser keep what it fetched (and V8 the compiled code of a
    // WebAssembly module it has optimised enough), as a deployed site would; by default every
    // load is fresh, for development.
    'cache-control': cacheable ? 'max-age=3600' : 'no-store',
    ...(isolated ? { 'cross-origin-opener-policy': 'same-origin' } : {}),
    ...(isolated || worker ? { 'cross-origin-embedder-policy': 'require-corp' } : {}),
  });
  createReadStream(file).pipe(response);
});

// A fixed default port for people (8173), a free one when it is taken or MESHQ_PORT=0.
const wanted = Number(process.env.MESHQ_PORT ?? 8173);
server.on('error', (error) => {
  if (error.code === 'EADDRINUSE' && wanted !== 0) {
    server.listen(0, '127.0.0.1');
  } else {
    throw error;
  }
});
server.listen(wanted, '127.0.0.1', () => {
  const { port } = server.address();
  console.log(`meshq demo: http://127.0.0.1:${port}/`);
});
