// docs/document.schema.json compiled with Ajv (draft 2020-12), for the Node
// and Playwright tests: the documents the core and the page write must pass
// the schema embedders are given. Ajv is a devDependency of web/.
import { readFileSync } from 'node:fs';

import Ajv2020 from '../web/node_modules/ajv/dist/2020.js';

const schema = JSON.parse(readFileSync(new URL('./document.schema.json', import.meta.url), 'utf8'));
const validate = new Ajv2020({ allErrors: true }).compile(schema);

/** The schema's complaints about `document` as "PATH: MESSAGE" lines; [] when it passes. */
export function schemaErrors(document) {
  if (validate(document)) return [];
  return validate.errors.map((error) => `${error.instancePath || '/'}: ${error.message} ${JSON.stringify(error.params)}`);
}
