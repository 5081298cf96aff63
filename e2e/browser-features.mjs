// The Chromium features the test browsers run without.
//
// Chromium's own omnibox popup, a WebUI page (chrome://omnibox-popup.top-chrome
// and its AI Mode variant), runs in a renderer of its own beside every test
// page, though a headless browser never shows it: in the document and
// embedding specs that renderer took 35 CPU-s of 250, and turning it off took
// them from 131-141 s to 98 s on two cores (254-274 -> 188 CPU-s).
//
// Chromium reads only the last --disable-features switch on its command line,
// and Playwright passes its own first: ours therefore repeats Playwright's list
// (playwright-core's chromiumSwitches, version 1.65.1, pinned by
// web/package-lock.json). browser-features.spec.mjs checks on the running
// browser that Playwright's list is still all in ours, and that no omnibox
// popup runs.

/** What Playwright 1.65.1 disables in Chromium. */
export const playwrightDisabledFeatures = [
  'AvoidUnnecessaryBeforeUnloadCheckSync',
  'DestroyProfileOnBrowserClose',
  'HttpsUpgrades',
  'HttpsFirstBalancedModeAutoEnable',
  'LensOverlay',
  'MediaRouter',
  'PaintHolding',
  'ThirdPartyStoragePartitioning',
  'AvoidCorsURLLoaderRestartOnRedirect',
  'TcpPortRandomizationWin',
  'OptimizationHints',
  'NetworkTimeServiceQuerying',
  'AimEnabled',
  'PreconnectToSearch',
  'msForceBrowserSignIn',
  'msEdgeUpdateLaunchServicesPreferredVersion',
];

/** The omnibox popup's WebUI pages. */
export const omniboxPopupFeatures = ['WebUIOmniboxPopup', 'WebUIOmniboxAimPopup', 'WebUIOmniboxFullPopup'];

/** The one --disable-features switch the test browsers are launched with. */
export const disableFeaturesArg = `--disable-features=${[...playwrightDisabledFeatures, ...omniboxPopupFeatures].join(',')}`;
