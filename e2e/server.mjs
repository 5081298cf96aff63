// Where the end-to-end tests serve the built site: one place for the ports,
// read by the Playwright config (webServer, baseURL) and by the CSP guard in
// csp-guard.mjs (the origin no request may leave, and the server whose
// violation reports it reads).
//
// One server per worker slot (Playwright's TEST_PARALLEL_INDEX, 0 to
// WORKER_SLOTS - 1, set in each worker's process; the runner's is slot 0):
// the violation reports a browser posts go to the server its page came from,
// so each worker reads its own. With one server, a report of one worker's
// test (posted late, under load) was taken by the other worker's test,
// failing that one and missing from its own.
export const WORKER_SLOTS = 2;
export const basePort = Number(process.env.ANISO_E2E_PORT ?? 4173);
export const slotPorts = Array.from({ length: WORKER_SLOTS }, (_, slot) => basePort + slot);
export const slotOrigins = slotPorts.map((slotPort) => `http://127.0.0.1:${slotPort}`);
export const origin = slotOrigins[Number(process.env.TEST_PARALLEL_INDEX ?? 0)] ?? slotOrigins[0];
