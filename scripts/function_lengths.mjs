// Function lengths of JavaScript modules, for scripts/check-function-length.sh (universal-ctags
// 5.9's JavaScript parser gives no end line). No parser: a tokenizer that skips comments,
// strings, template literals (with their ${...} parts) and regular expressions, then takes each
// `{` that opens a function body: after `=>`, or after the `)` of a parameter list that follows
// `function`, `function*` or a method name (not a control keyword such as `if` or `for`).
// A function's length runs from the line of its name (an arrow: of its parameter list) to the
// line of its closing brace, both included.
// Usage: node scripts/function_lengths.mjs FILE...; prints "LINES<TAB>FILE:LINE<TAB>NAME" per
// function, e.g. "122	targets/hlsl/generate_hlsl.mjs:250	flatten".
import fs from 'node:fs';

const CONTROL = new Set(['if', 'for', 'while', 'switch', 'catch', 'with', 'return', 'typeof', 'await']);
// After these tokens a `/` starts a regular expression, not a division.
const BEFORE_REGEX_WORDS = new Set(['return', 'typeof', 'case', 'in', 'of', 'new', 'delete', 'void', 'throw', 'else',
  'do', 'yield', 'await']);

function tokenize(text) {
  const tokens = [];
  let i = 0;
  let line = 1;
  let braceDepth = 0;
  const templateDepths = [];  // the brace depth at which each open ${ started
  const push = (value) => tokens.push({ value, line });
  const regexAllowed = () => {
    const last = tokens[tokens.length - 1];
    if (!last) return true;
    if (/^[\w$]+$/.test(last.value)) return BEFORE_REGEX_WORDS.has(last.value);
    return ![')', ']', '}', 'STRING', 'NUMBER'].includes(last.value);
  };
  // The rest of a template literal, from after its ` (or the } that closes a ${...}).
  const readTemplate = () => {
    while (i < text.length) {
      const c = text[i];
      if (c === '\\') { i += 2; continue; }
      if (c === '\n') line++;
      if (c === '`') { i++; push('STRING'); return; }
      if (c === '$' && text[i + 1] === '{') {
        i += 2;
        templateDepths.push(braceDepth++);
        push('${');
        return;
      }
      i++;
    }
  };
  while (i < text.length) {
    const c = text[i];
    if (c === '\n') { line++; i++; continue; }
    if (/\s/.test(c)) { i++; continue; }
    if (c === '/' && text[i + 1] === '/') {
      while (i < text.length && text[i] !== '\n') i++;
      continue;
    }
    if (c === '/' && text[i + 1] === '*') {
      i += 2;
      while (i < text.length && !(text[i] === '*' && text[i + 1] === '/')) {
        if (text[i] === '\n') line++;
        i++;
      }
      i += 2;
      continue;
    }
    if (c === '"' || c === "'") {
      i++;
      while (i < text.length && text[i] !== c) i += text[i] === '\\' ? 2 : 1;
      i++;
      push('STRING');
      continue;
    }
    if (c === '`') { i++; readTemplate(); continue; }
    if (c === '/' && regexAllowed()) {
      i++;
      let inClass = false;
      while (i < text.length && (inClass || text[i] !== '/')) {
        if (text[i] === '\\') i++;
        else if (text[i] === '[') inClass = true;
        else if (text[i] === ']') inClass = false;
        i++;
      }
      i++;
      while (/[a-z]/i.test(text[i] || '')) i++;
      push('STRING');
      continue;
    }
    if (/[\w$]/.test(c)) {
      let end = i;
      while (end < text.length && /[\w$]/.test(text[end])) end++;
      push(/^\d/.test(c) ? 'NUMBER' : text.slice(i, end));
      i = end;
      continue;
    }
    if (c === '=' && text[i + 1] === '>') { push('=>'); i += 2; continue; }
    if (c === '{') { braceDepth++; push('{'); i++; continue; }
    if (c === '}') {
      braceDepth--;
      i++;
      if (templateDepths.length && templateDepths[templateDepths.length - 1] === braceDepth) {
        templateDepths.pop();
        push('}$');
        readTemplate();
        continue;
      }
      push('}');
      continue;
    }
    push(c);
    i++;
  }
  return tokens;
}

// The index of the `(` that matches the `)` at `index`.
function openingParenthesis(tokens, index) {
  let depth = 0;
  for (let k = index; k >= 0; k--) {
    if (tokens[k].value === ')') depth++;
    else if (tokens[k].value === '(' && --depth === 0) return k;
  }
  return -1;
}

// Where the function whose body opens at `index` starts, and its name; null for other blocks.
function functionAt(tokens, index) {
  const before = tokens[index - 1];
  if (!before) return null;
  if (before.value === '=>') {
    const parameters = tokens[index - 2].value === ')' ? openingParenthesis(tokens, index - 2) : index - 2;
    const assigned = tokens[parameters - 1]?.value === '=' ? tokens[parameters - 2]?.value : '(arrow)';
    return { line: tokens[Math.max(parameters, 0)].line, name: assigned };
  }
  if (before.value !== ')') return null;
  const open = openingParenthesis(tokens, index - 1);
  const head = tokens[open - 1];
  if (!head) return null;
  if (head.value === 'function' || head.value === '*') return { line: head.line, name: '(function)' };
  if (/^[\w$]+$/.test(head.value) && !CONTROL.has(head.value)) return { line: head.line, name: head.value };
  return null;
}

for (const file of process.argv.slice(2)) {
  const tokens = tokenize(fs.readFileSync(file, 'utf8'));
  const open = [];
  tokens.forEach((token, index) => {
    if (token.value === '{') open.push(functionAt(tokens, index));
    else if (token.value === '${') open.push(null);
    else if (token.value === '}' || token.value === '}$') {
      const start = open.pop();
      if (start) console.log(`${token.line - start.line + 1}\t${file}:${start.line}\t${start.name}`);
    }
  });
  if (open.length) {
    console.error(`function_lengths: ${file}: unbalanced braces (${open.length} open at the end)`);
    process.exitCode = 1;
  }
}
