// Where the end-to-end tests serve the built site: one place for the port,
// read by the Playwright config (webServer, baseURL) and by the CSP guard in
// support.mjs (the origin no request may leave).
export const port = Number(process.env.ANISO_E2E_PORT ?? 4173);
export const origin = `http://127.0.0.1:${port}`;
