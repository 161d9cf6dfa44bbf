// source_text.mjs - the one comment stripper of the JS drivers (slangc.mjs, hlsl/generate_hlsl.mjs,
// check_targets.mjs): the code of C-dialect source text with // and /* */ comments removed, so
// that directives and patterns inside comments are ignored. String literals are copied whole
// ("/*" inside one opens no comment; escaped quotes stay inside it), or blanked to "" on request.

// The code of one line. `inBlock` says whether a block comment is open at the start of the line
// and comes back for the next line; a closed block comment leaves one space. With
// blankStrings, each string literal becomes "".
export function codeOfLine(line, inBlock, { blankStrings = false } = {}) {
  let code = '';
  let i = 0;
  while (i < line.length) {
    if (inBlock) {
      const end = line.indexOf('*/', i);
      if (end < 0) return { code, inBlock: true };
      i = end + 2;
      inBlock = false;
      code += ' ';
    } else if (line.startsWith('//', i)) {
      break;
    } else if (line.startsWith('/*', i)) {
      inBlock = true;
      i += 2;
    } else if (line[i] === '"') {
      let j = i + 1;
      while (j < line.length && line[j] !== '"') j += line[j] === '\\' ? 2 : 1;
      code += blankStrings ? '""' : line.slice(i, j + 1);
      i = j + 1;
    } else {
      code += line[i++];
    }
  }
  return { code, inBlock };
}

// The code of each line of `lines` (block comments may span lines), e.g. for directive parsing.
export function codeLines(lines, options = {}) {
  let inBlock = false;
  return lines.map((line) => {
    const parsed = codeOfLine(line, inBlock, options);
    inBlock = parsed.inBlock;
    return parsed.code;
  });
}

// The whole text without comments and with string literals blanked, line structure kept (the
// line numbers of matches stay those of the source).
export function codeOnly(text) {
  return codeLines(text.split('\n'), { blankStrings: true }).join('\n');
}
