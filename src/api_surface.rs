//! The public surface counted from the sources and held to docs/api.md's
//! table: a `pub` item or a re-export added, or one made `pub(crate)`,
//! fails this test until the page says so.
//!
//! What is counted is what `cargo doc --no-deps -p taut` lists in
//! `all.html` (structs, enums, traits, functions, constants, statics, type
//! aliases; modules and methods not): every `pub` item of a module whose
//! path is public, and every item a public module re-exports (`pub use`,
//! globs and re-exported modules followed) from a private one, counted once,
//! under the first public module, in path order, that re-exports it (the
//! root last). Items under `#[cfg(feature = ...)]` are left out (the
//! documentation is built without features), and `#[cfg(test)]` modules.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

type ModPath = Vec<String>;

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    Punct(char),
}

/// A module's `pub` items and its `use` trees (public or not, as text with
/// `as` written `@`).
#[derive(Default)]
struct Module {
    public: bool,
    items: Vec<String>,
    uses: Vec<(bool, String)>,
}

/// The text without comments, string and character literals (each
/// literal left as `""` or `' '`), so that braces count.
fn strip(s: &str) -> String {
    let b: Vec<char> = s.chars().collect();
    let (mut out, mut i) = (String::new(), 0);
    let at = |i: usize, p: &str| b[i..].iter().take(p.len()).copied().eq(p.chars());
    while i < b.len() {
        let c = b[i];
        if at(i, "//") {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if at(i, "/*") {
            while !at(i, "*/") {
                i += 1;
            }
            i += 2;
            out.push(' ');
        } else if c == 'r'
            && (i == 0 || !(b[i - 1].is_alphanumeric() || b[i - 1] == '_'))
            && b[i + 1..].iter().take_while(|&&h| h == '#').count() + i + 1 < b.len()
            && b[i + 1 + b[i + 1..].iter().take_while(|&&h| h == '#').count()] == '"'
        {
            let hashes = b[i + 1..].iter().take_while(|&&h| h == '#').count();
            let end: String = std::iter::once('"')
                .chain("#".repeat(hashes).chars())
                .collect();
            i += hashes + 2;
            while !at(i, &end) {
                i += 1;
            }
            i += end.len();
            out.push_str("\"\"");
        } else if c == '"' {
            i += 1;
            while b[i] != '"' {
                i += if b[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' && char_literal_len(&b[i..]).is_some() {
            i += char_literal_len(&b[i..]).unwrap();
            out.push_str("' '");
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// The length of a character literal starting here (`'a'`, `'\n'`,
/// `'\u{7f}'`), or `None` for a lifetime.
fn char_literal_len(b: &[char]) -> Option<usize> {
    match b.get(1)? {
        '\\' if b.get(2) == Some(&'u') => {
            let close = b.iter().position(|&c| c == '}')?;
            (b.get(close + 1) == Some(&'\'')).then_some(close + 2)
        }
        '\\' => (b.get(3) == Some(&'\'')).then_some(4),
        '\'' => None,
        _ => (b.get(2) == Some(&'\'')).then_some(3),
    }
}

fn tokens(s: &str) -> Vec<Tok> {
    let (mut out, mut word) = (Vec::new(), String::new());
    for c in strip(s).chars() {
        if c.is_alphanumeric() || c == '_' {
            word.push(c);
            continue;
        }
        if !word.is_empty() {
            out.push(Tok::Ident(std::mem::take(&mut word)));
        }
        if !c.is_whitespace() {
            out.push(Tok::Punct(c));
        }
    }
    if !word.is_empty() {
        out.push(Tok::Ident(word));
    }
    out
}

fn is(t: Option<&Tok>, w: &str) -> bool {
    matches!(t, Some(Tok::Ident(x)) if x == w)
}

fn punct(t: Option<&Tok>, c: char) -> bool {
    t == Some(&Tok::Punct(c))
}

/// The index after the block whose `{` is at `i`.
fn skip_block(t: &[Tok], mut i: usize) -> usize {
    let mut depth = 0;
    loop {
        match &t[i] {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
}

struct Crate {
    src: PathBuf,
    mods: HashMap<ModPath, Module>,
}

impl Crate {
    fn file_of(&self, m: &ModPath) -> PathBuf {
        if m.is_empty() {
            return self.src.join("lib.rs");
        }
        let base = self.src.join(m.join("/"));
        let flat = base.with_extension("rs");
        if flat.exists() {
            flat
        } else {
            base.join("mod.rs")
        }
    }

    fn parse_file(&mut self, m: ModPath, public: bool) {
        let text = std::fs::read_to_string(self.file_of(&m)).unwrap();
        let t = tokens(&text);
        self.parse(m, &t, 0, public);
    }

    /// Parse a module's body from `i` to its closing brace (or the end);
    /// the index after it.
    fn parse(&mut self, m: ModPath, t: &[Tok], mut i: usize, public: bool) -> usize {
        self.mods.entry(m.clone()).or_default().public = public;
        let (mut depth, mut cfg) = (0usize, None::<String>);
        while i < t.len() {
            match &t[i] {
                Tok::Punct('#') if punct(t.get(i + 1), '[') => {
                    let start = i + 2;
                    let (mut d, mut j) = (1, start);
                    while d > 0 {
                        match t[j] {
                            Tok::Punct('[') => d += 1,
                            Tok::Punct(']') => d -= 1,
                            _ => {}
                        }
                        j += 1;
                    }
                    if is(t.get(start), "cfg") {
                        let words = t[start..j]
                            .iter()
                            .filter_map(|x| match x {
                                Tok::Ident(w) => Some(w.as_str()),
                                _ => None,
                            })
                            .collect::<Vec<_>>()
                            .join(" ");
                        cfg = Some(words);
                    }
                    i = j;
                    continue;
                }
                Tok::Punct('{') => {
                    depth += 1;
                    cfg = None;
                }
                Tok::Punct('}') => {
                    if depth == 0 {
                        return i + 1;
                    }
                    depth -= 1;
                }
                Tok::Punct(';') => cfg = None,
                Tok::Ident(w) if depth == 0 => {
                    let (mut j, mut vis) = (i, None);
                    if w == "pub" {
                        vis = Some(!punct(t.get(i + 1), '('));
                        j += 1;
                        if punct(t.get(j), '(') {
                            while !punct(t.get(j), ')') {
                                j += 1;
                            }
                            j += 1;
                        }
                    }
                    // qualifiers: const fn, unsafe fn, async fn, extern "C" fn
                    loop {
                        let next_is_fnish = ["fn", "unsafe", "async", "extern"]
                            .iter()
                            .any(|k| is(t.get(j + 1), k));
                        if (is(t.get(j), "const") && next_is_fnish)
                            || is(t.get(j), "unsafe")
                            || is(t.get(j), "async")
                        {
                            j += 1;
                        } else if is(t.get(j), "extern") && punct(t.get(j + 1), '"') {
                            j += 3;
                        } else {
                            break;
                        }
                    }
                    let kind = match t.get(j) {
                        Some(Tok::Ident(k)) => k.clone(),
                        _ => {
                            i += 1;
                            continue;
                        }
                    };
                    const KINDS: [&str; 10] = [
                        "struct", "enum", "trait", "fn", "const", "type", "static", "union", "mod",
                        "use",
                    ];
                    if !KINDS.contains(&kind.as_str()) {
                        i += 1;
                        continue;
                    }
                    let c = cfg.take().unwrap_or_default();
                    let feature = c.contains("feature");
                    let test_only = c.split(' ').any(|x| x == "test") && !c.contains("not");
                    let is_pub = vis == Some(true) && !feature;
                    j += 1;
                    match kind.as_str() {
                        "mod" => {
                            let Some(Tok::Ident(name)) = t.get(j) else {
                                panic!("a module without a name in {m:?}")
                            };
                            let mut sub = m.clone();
                            sub.push(name.clone());
                            let inline = punct(t.get(j + 1), '{');
                            i = match (test_only, inline) {
                                (true, true) => skip_block(t, j + 1),
                                (true, false) => j + 2,
                                (false, true) => self.parse(sub, t, j + 2, is_pub),
                                (false, false) => {
                                    self.parse_file(sub, is_pub);
                                    j + 2
                                }
                            };
                            continue;
                        }
                        "use" => {
                            let mut body = String::new();
                            while !punct(t.get(j), ';') {
                                match &t[j] {
                                    Tok::Ident(x) if x == "as" => body.push('@'),
                                    Tok::Ident(x) => body.push_str(x),
                                    Tok::Punct(p) => body.push(*p),
                                }
                                j += 1;
                            }
                            self.mods.get_mut(&m).unwrap().uses.push((is_pub, body));
                            i = j + 1;
                            continue;
                        }
                        _ => {
                            if let (true, Some(Tok::Ident(name))) = (is_pub, t.get(j)) {
                                self.mods.get_mut(&m).unwrap().items.push(name.clone());
                            }
                            i = j;
                            continue;
                        }
                    }
                }
                _ => {}
            }
            i += 1;
        }
        i
    }

    /// Every module on the path public.
    fn is_public(&self, m: &ModPath) -> bool {
        (1..=m.len()).all(|k| self.mods[&m[..k].to_vec()].public)
    }

    /// A use path's module and last segment, from module `m`.
    fn resolve(&self, m: &ModPath, segs: &[String]) -> Option<(ModPath, String)> {
        let mut base = m.clone();
        let mut rest = segs;
        match segs[0].as_str() {
            "crate" => {
                base.clear();
                rest = &segs[1..];
            }
            "self" => rest = &segs[1..],
            "super" => {
                while rest.first().map(String::as_str) == Some("super") {
                    base.pop();
                    rest = &rest[1..];
                }
            }
            _ => {}
        }
        let (last, dirs) = rest.split_last()?;
        for s in dirs {
            base.push(s.clone());
            if !self.mods.contains_key(&base) {
                return None;
            }
        }
        Some((base, last.clone()))
    }

    /// The items `name` in module `dm` stands for: an item of it, every
    /// item of a module of that name, or what a re-export of it names.
    fn lookup(&self, dm: &ModPath, name: &str, depth: usize) -> Vec<(ModPath, String)> {
        let Some(md) = self.mods.get(dm) else {
            return vec![];
        };
        if depth > 10 {
            return vec![];
        }
        if md.items.iter().any(|x| x == name) {
            return vec![(dm.clone(), name.to_string())];
        }
        let mut sub = dm.clone();
        sub.push(name.to_string());
        if self.mods.contains_key(&sub) {
            return self.all_items(&sub);
        }
        let mut out = vec![];
        for (_, body) in md.uses.iter().filter(|u| u.0) {
            for segs in expand(body) {
                let (orig, alias) = split_alias(segs.last().unwrap());
                let mut path = segs[..segs.len() - 1].to_vec();
                path.push(orig.clone());
                let Some((rm, _)) = self.resolve(dm, &path) else {
                    continue;
                };
                if orig == "*" {
                    out.extend(self.lookup(&rm, name, depth + 1));
                } else if alias.as_deref().unwrap_or(&orig) == name {
                    out.extend(self.lookup(&rm, &orig, depth + 1));
                }
            }
        }
        out
    }

    fn all_items(&self, m: &ModPath) -> Vec<(ModPath, String)> {
        let mut out: Vec<_> = self.mods[m]
            .items
            .iter()
            .map(|n| (m.clone(), n.clone()))
            .collect();
        for (k, md) in &self.mods {
            if k.len() == m.len() + 1 && k.starts_with(m) && md.public {
                out.extend(self.all_items(k));
            }
        }
        out
    }

    /// The number of public items under each top-level module (`root`:
    /// the crate's own).
    fn surface(&self) -> BTreeMap<String, usize> {
        let top = |m: &ModPath| m.first().cloned().unwrap_or_else(|| "root".into());
        let mut counted: HashMap<(ModPath, String), String> = HashMap::new();
        for (m, md) in &self.mods {
            if self.is_public(m) {
                for n in &md.items {
                    counted.insert((m.clone(), n.clone()), top(m));
                }
            }
        }
        let mut order: Vec<&ModPath> = self.mods.keys().collect();
        order.sort_by_key(|m| (m.is_empty(), (*m).clone()));
        for m in order.into_iter().filter(|m| self.is_public(m)) {
            for (_, body) in self.mods[m].uses.iter().filter(|u| u.0) {
                for segs in expand(body) {
                    let (orig, _) = split_alias(segs.last().unwrap());
                    let mut path = segs[..segs.len() - 1].to_vec();
                    path.push(orig.clone());
                    let Some((rm, _)) = self.resolve(m, &path) else {
                        continue;
                    };
                    let keys = if orig == "*" {
                        self.glob(&rm)
                    } else {
                        self.lookup(&rm, &orig, 0)
                    };
                    for k in keys {
                        counted.entry(k).or_insert_with(|| top(m));
                    }
                }
            }
        }
        let mut by_top = BTreeMap::new();
        for t in counted.into_values() {
            *by_top.entry(t).or_insert(0) += 1;
        }
        by_top
    }

    /// What `pub use rm::*` brings: rm's items and its own re-exports.
    fn glob(&self, rm: &ModPath) -> Vec<(ModPath, String)> {
        let Some(md) = self.mods.get(rm) else {
            return vec![];
        };
        let mut keys: Vec<_> = md.items.iter().map(|n| (rm.clone(), n.clone())).collect();
        for (_, body) in md.uses.iter().filter(|u| u.0) {
            for segs in expand(body) {
                let (orig, alias) = split_alias(segs.last().unwrap());
                if orig == "*" {
                    let mut path = segs[..segs.len() - 1].to_vec();
                    path.push(orig);
                    if let Some((r2, _)) = self.resolve(rm, &path)
                        && let Some(m2) = self.mods.get(&r2)
                    {
                        keys.extend(m2.items.iter().map(|n| (r2.clone(), n.clone())));
                    }
                } else {
                    keys.extend(self.lookup(rm, alias.as_deref().unwrap_or(&orig), 0));
                }
            }
        }
        keys
    }
}

/// `a` or `a@b` (`a as b`).
fn split_alias(last: &str) -> (String, Option<String>) {
    match last.split_once('@') {
        Some((a, b)) => (a.to_string(), Some(b.to_string())),
        None => (last.to_string(), None),
    }
}

/// A use tree's paths: `a::{b, c::{d@e, *}}` → `a::b`, `a::c::d@e`, `a::c::*`.
fn expand(body: &str) -> Vec<Vec<String>> {
    fn rec(prefix: &[String], s: &str, out: &mut Vec<Vec<String>>) {
        let brace = s.find('{');
        let comma = s.find(',');
        match brace {
            Some(k) if comma.is_none_or(|c| k < c) => {
                let mut p = prefix.to_vec();
                p.extend(
                    s[..k]
                        .split("::")
                        .filter(|x| !x.is_empty())
                        .map(String::from),
                );
                let inner = &s[k + 1..s.len() - 1];
                let (mut depth, mut cur) = (0, String::new());
                for ch in inner.chars() {
                    match ch {
                        ',' if depth == 0 => {
                            if !cur.is_empty() {
                                rec(&p, &std::mem::take(&mut cur), out);
                            }
                            continue;
                        }
                        '{' => depth += 1,
                        '}' => depth -= 1,
                        _ => {}
                    }
                    cur.push(ch);
                }
                if !cur.is_empty() {
                    rec(&p, &cur, out);
                }
            }
            _ => {
                let mut p = prefix.to_vec();
                p.extend(s.split("::").map(String::from));
                out.push(p);
            }
        }
    }
    let mut out = vec![];
    rec(&[], body, &mut out);
    out
}

/// docs/api.md's count: its total (`**N public items**`) and its table's
/// rows (`` | `module` | N | ``, the root's `| the root | N |`).
fn documented(page: &str) -> (usize, BTreeMap<String, usize>) {
    let total = page
        .split("**")
        .find_map(|s| s.strip_suffix(" public items")?.parse().ok())
        .expect("docs/api.md gives its total as **N public items**");
    let mut rows = BTreeMap::new();
    for line in page.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 4 {
            continue;
        }
        let name = match cells[1] {
            "the root" => "root".to_string(),
            c if c.starts_with('`') && c.ends_with('`') && c.len() > 2 => {
                c.trim_matches('`').to_string()
            }
            _ => continue,
        };
        if let Ok(n) = cells[2].parse() {
            rows.insert(name, n);
        }
    }
    (total, rows)
}

#[test]
fn api_md_counts_the_public_items() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut krate = Crate {
        src: root.join("src"),
        mods: HashMap::new(),
    };
    krate.parse_file(vec![], true);
    let found = krate.surface();
    let page = std::fs::read_to_string(root.join("docs/api.md")).unwrap();
    let (total, rows) = documented(&page);
    let sum: usize = found.values().sum();
    assert_eq!(
        (total, &rows),
        (sum, &found),
        "docs/api.md's count of public items (left) is not the library's \
         (right): update its total and table (the count is the one of \
         `cargo doc --no-deps -p taut`'s all.html, api.md gives the command)"
    );
}

#[test]
fn the_scanner_reads_what_it_should() {
    let t = strip("a /* { */ \"}\" '{' 'a r#\"}\"# // }\nb");
    assert_eq!(t.matches('{').count(), t.matches('}').count(), "{t}");
    assert_eq!(
        expand("self::a::{B,c::{D@E,*}}"),
        vec![
            vec!["self", "a", "B"],
            vec!["self", "a", "c", "D@E"],
            vec!["self", "a", "c", "*"],
        ]
        .into_iter()
        .map(|v| v.into_iter().map(String::from).collect::<Vec<_>>())
        .collect::<Vec<_>>()
    );
    let (total, rows) = documented("**7 public items**\n| the root | 1 |\n| `scene` | 6 | x |\n");
    assert_eq!(total, 7);
    assert_eq!(rows.values().sum::<usize>(), 7);
}
