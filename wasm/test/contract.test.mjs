// One contract: anisoform-wasm.d.ts declares the request objects, the core's
// parser (core/include/anisoform/op.h) accepts them. Every declaration tagged
// `@schema PATH` must list exactly the keys (or, for a union, the kinds) that
// the core's op_schema() gives for PATH, and every PATH must be declared, so a
// field added to one and not the other fails here.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { before, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { loadAnisoform } from '../node-support.mjs';

const declarationsPath = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', 'js', 'anisoform-wasm.d.ts');

let wasm;
before(async () => {
  ({ wasm } = await loadAnisoform());
});

// {name -> {path, body (interface) | union (type)}} of the tagged declarations.
function taggedDeclarations(text) {
  const found = new Map();
  const pattern = /\/\*\* @schema ([\w.]+) \*\/\nexport (?:interface (\w+) \{\n([\s\S]*?)\n\}|type (\w+) = ([^;]+);)/g;
  for (const match of text.matchAll(pattern)) {
    const [, schemaPath, interfaceName, body, typeName, union] = match;
    found.set(interfaceName ?? typeName, { schemaPath, body, union });
  }
  return found;
}

// The top-level keys of an interface body (two-space indent; comments skipped).
const interfaceKeys = (body) => [...body.matchAll(/^ {2}(\w+)\??:/gm)].map((m) => m[1]);

// A union's kinds: `{ key: ... }` members give their key; a named member its
// `type` literal, or else its first key (VertexRegion -> 'vertices').
function unionKinds(union, declarations) {
  return union.split('|').map((member) => member.trim()).map((member) => {
    const inline = member.match(/^\{ (\w+):/);
    if (inline) return inline[1];
    const declared = declarations.get(member);
    assert.ok(declared?.body, `union member ${member} is not a tagged interface`);
    return declared.body.match(/^ {2}type: '(\w+)'/m)?.[1] ?? interfaceKeys(declared.body)[0];
  });
}

test('every request object of the .d.ts declares exactly the keys the core parses', () => {
  const schema = wasm.opSchema();
  const declarations = taggedDeclarations(readFileSync(declarationsPath, 'utf8'));
  const declaredPaths = new Map([...declarations].map(([name, d]) => [d.schemaPath, { name, ...d }]));
  assert.deepEqual([...declaredPaths.keys()].sort(), Object.keys(schema).sort(),
    'the tagged declarations and the core schema cover the same objects');
  for (const [schemaPath, keys] of Object.entries(schema)) {
    const { name, body, union } = declaredPaths.get(schemaPath);
    const declared = body !== undefined ? interfaceKeys(body) : unionKinds(union, declarations);
    assert.deepEqual([...declared].sort(), [...keys].sort(), `${name} (@schema ${schemaPath})`);
  }
});

test('the check above can fail: a key the core does not parse is refused by name', () => {
  const session = new wasm.Session();
  try {
    assert.throws(() => session.deform({ method: 'anarap', colour: 'red' }), /op has an unknown field 'colour'/);
  } finally {
    session.delete();
  }
});
