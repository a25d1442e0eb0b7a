// ESLint for the designer's modules (npm run lint): native ES modules in the browser, whose
// text always reaches the page as text (no HTML parsed from strings), lines of 100 columns.
import js from "@eslint/js";
import globals from "globals";

const HTML = "build elements (dom.js el, textContent) rather than parsing HTML from strings";

export default [
  { ignores: ["**/vendor/**", "node_modules/**"] },
  js.configs.recommended,
  {
    files: ["**/*.js"],
    languageOptions: { ecmaVersion: 2024, sourceType: "module", globals: globals.browser },
    rules: {
      "no-restricted-syntax": ["error", ...[
        "AssignmentExpression > MemberExpression.left[property.name=/^(inner|outer)HTML$/]",
        "CallExpression[callee.property.name='insertAdjacentHTML']",
        "CallExpression[callee.object.name='document'][callee.property.name=/^write(ln)?$/]",
      ].map((selector) => ({ selector, message: HTML }))],
      "eqeqeq": ["error", "always", { null: "ignore" }],
      "no-var": "error",
      "prefer-const": "error",
      "max-len": ["error", { code: 100, ignoreUrls: true }],
    },
  },
  { files: ["eslint.config.js"], languageOptions: { globals: globals.node } },
];
