// A static file server for the built site, sending the strict
// Content-Security-Policy the app must run under on every response (pages,
// scripts, the worker's script, the WASM). Node's standard library only: it
// serves `scripts/run.sh` and the Playwright tests the same way.
//
//   node scripts/serve-static.mjs DIR [--port N] [--host H]
//
// Violations: the policy names a report endpoint on this server, so
// violations inside the solver's Web Worker — which never reach a page's
// `securitypolicyviolation` listener — are seen too. Each report is printed on
// stderr and kept; GET /__csp-reports returns them as JSON and DELETE returns
// and clears them (the end-to-end tests take them after every test).
import { createReadStream, statSync } from 'node:fs';
import { createServer } from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

/** What the site, the examples and the package are tested under (README, Security). */
export const CONTENT_SECURITY_POLICY = [
  "default-src 'self'",
  // WebAssembly.instantiate needs 'wasm-unsafe-eval'; JS eval stays forbidden.
  "script-src 'self' 'wasm-unsafe-eval'",
  "worker-src 'self' blob:",
  // three.js and the UI set element.style; no inline <style> is needed.
  "style-src 'self' 'unsafe-inline'",
  // Canvas exports and screenshots go through data: and blob: URLs.
  "img-src 'self' data: blob:",
].join('; ');

export const CSP_REPORT_PATH = '/__csp-report';
export const CSP_REPORTS_PATH = '/__csp-reports';

const MIME_TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.wasm': 'application/wasm',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.ico': 'image/x-icon',
  '.txt': 'text/plain; charset=utf-8',
  '.map': 'application/json',
};

const REPORT_BODY_LIMIT = 64 * 1024;

/** Starts serving `root`; resolves with the listening http.Server. */
export function serveStatic({ root, port, host = '127.0.0.1', log = (line) => process.stderr.write(`${line}\n`) }) {
  const rootDir = path.resolve(root);
  const reports = [];

  const server = createServer((request, response) => {
    // An absolute report URL: a blob: worker inherits the page's policy, and
    // a relative one would resolve against its blob: URL.
    const reportUri = request.headers.host ? `http://${request.headers.host}${CSP_REPORT_PATH}` : CSP_REPORT_PATH;
    response.setHeader('Content-Security-Policy', `${CONTENT_SECURITY_POLICY}; report-uri ${reportUri}`);
    response.setHeader('X-Content-Type-Options', 'nosniff');
    const url = new URL(request.url, 'http://localhost');

    if (url.pathname === CSP_REPORT_PATH && request.method === 'POST') {
      readBody(request, (body) => {
        const report = parseReport(body);
        reports.push(report);
        log(`CSP violation: ${JSON.stringify(report)}`);
        response.writeHead(204).end();
      });
      return;
    }
    if (url.pathname === CSP_REPORTS_PATH) {
      // DELETE takes them: the reports it clears are the ones it returns, so
      // none posted meanwhile is lost between a read and a clear.
      const taken = request.method === 'DELETE' ? reports.splice(0) : reports;
      response.writeHead(200, { 'Content-Type': 'application/json', 'Cache-Control': 'no-store' });
      response.end(JSON.stringify(taken));
      return;
    }
    if (request.method !== 'GET' && request.method !== 'HEAD') {
      response.writeHead(405, { Allow: 'GET, HEAD' }).end();
      return;
    }

    let file;
    try {
      file = path.join(rootDir, decodeURIComponent(url.pathname));
    } catch {
      response.writeHead(400).end();
      return;
    }
    if (file !== rootDir && !file.startsWith(rootDir + path.sep)) {
      response.writeHead(403).end();
      return;
    }
    let stats = statOrNull(file);
    if (stats?.isDirectory()) {
      file = path.join(file, 'index.html');
      stats = statOrNull(file);
    }
    if (!stats?.isFile()) {
      response.writeHead(404, { 'Content-Type': 'text/plain; charset=utf-8' }).end(`Not found: ${url.pathname}\n`);
      return;
    }
    // Every use revalidates (no-cache: a rebuilt site is never stale), and an
    // unchanged file is answered 304. That keeps the browser's cache entry,
    // and with it V8's compiled code: a reload does not compile the solver's
    // WASM module (about 1.7 s of CPU here) and the scripts again. (The
    // end-to-end tests' browser contexts keep no such cache.)
    const etag = `"${stats.size.toString(16)}-${Math.trunc(stats.mtimeMs).toString(16)}"`;
    const validators = { ETag: etag, 'Last-Modified': stats.mtime.toUTCString(), 'Cache-Control': 'no-cache' };
    if (request.headers['if-none-match'] === etag) {
      response.writeHead(304, validators).end();
      return;
    }
    response.writeHead(200, {
      'Content-Type': MIME_TYPES[path.extname(file).toLowerCase()] ?? 'application/octet-stream',
      'Content-Length': stats.size,
      ...validators,
    });
    if (request.method === 'HEAD') response.end();
    else createReadStream(file).pipe(response);
  });

  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, host, () => resolve(server));
  });
}

function statOrNull(file) {
  try {
    return statSync(file);
  } catch {
    return null;
  }
}

function readBody(request, done) {
  const chunks = [];
  let size = 0;
  request.on('data', (chunk) => {
    size += chunk.length;
    if (size <= REPORT_BODY_LIMIT) chunks.push(chunk);
  });
  request.on('end', () => done(Buffer.concat(chunks).toString('utf8')));
}

// Chromium posts {"csp-report": {...}} (application/csp-report).
function parseReport(body) {
  try {
    const parsed = JSON.parse(body);
    return parsed['csp-report'] ?? parsed;
  } catch {
    return { unparsed: body };
  }
}

function parseArguments(argv) {
  const options = { root: null, port: 8080, host: '127.0.0.1' };
  for (let a = 0; a < argv.length; ++a) {
    const arg = argv[a];
    if (arg === '--port') options.port = Number(argv[++a]);
    else if (arg === '--host') options.host = argv[++a];
    else if (!arg.startsWith('--') && options.root === null) options.root = arg;
    else throw new Error(`unknown argument '${arg}'`);
  }
  if (options.root === null) throw new Error('the folder to serve is missing');
  if (!statOrNull(options.root)?.isDirectory()) {
    throw new Error(`${options.root} is not a folder (build the site first: npm run build --prefix web)`);
  }
  if (!Number.isInteger(options.port) || options.port < 0 || options.port > 65535) {
    throw new Error(`--port needs a port number, got '${argv[argv.indexOf('--port') + 1]}'`);
  }
  return options;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  let options;
  try {
    options = parseArguments(process.argv.slice(2));
  } catch (error) {
    process.stderr.write(`serve-static: ${error.message}\nusage: node scripts/serve-static.mjs DIR [--port N] [--host H]\n`);
    process.exit(2);
  }
  serveStatic(options).then(
    (server) => {
      const { address, port } = server.address();
      process.stdout.write(`serve-static: ${options.root} on http://${address}:${port}/ with the strict CSP\n`);
    },
    (error) => {
      process.stderr.write(`serve-static: ${error.message}\n`);
      process.exit(1);
    },
  );
}
