//! The extension-parity file (`tests/extension_parity.txt`) against the live extension strings
//! of Mesa held to ES 2.0 and of Strata: it lists every extension Mesa offers on an ES 2.0
//! context exactly once, says "advertised" exactly for those Strata advertises (naming tests
//! that cover each), and Strata advertises nothing Mesa does not. And piglit's scope
//! (`tests/piglit/verdict.rs`) holds every GL and EGL extension the drop-in library
//! advertises, so that no exception line can excuse a test of something Strata claims. And the
//! mutation table (`tests/mutants/extensions.tsv`) has a line for every advertised extension.

mod programs;
mod support;
#[path = "piglit/verdict.rs"]
#[allow(dead_code)]
mod verdict;

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use programs::harness::strata_context;
use programs::{H, W};
use strata_client::Calls;
use support::mesa::MesaGl;
use support::Daemon;

const GL_VERSION: u32 = 0x1F02;
const GL_EXTENSIONS: u32 = 0x1F03;

/// What the parity file says of one extension.
#[derive(Debug, PartialEq)]
enum Status {
    /// Advertised, with the test files (under `tests/`) that cover it.
    Advertised(Vec<String>),
    /// Not advertised, because wgpu cannot express it: the reason.
    Excused(String),
    /// Not advertised yet: what it needs.
    Missing(String),
}

/// The parity file's lines, by extension name.
fn parity_file() -> BTreeMap<String, Status> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/extension_parity.txt");
    let text = std::fs::read_to_string(&path).expect("tests/extension_parity.txt");
    let mut out = BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.splitn(3, '|').map(str::trim).collect();
        let [name, status, detail] = fields[..] else { panic!("line {}: NAME | STATUS | DETAIL: {line}", i + 1) };
        assert!(!detail.is_empty(), "line {}: {name} gives no detail", i + 1);
        let status = match status {
            "advertised" => {
                let files = detail.split(':').next().unwrap_or_default();
                Status::Advertised(files.split(',').map(|f| f.trim().to_string()).collect())
            }
            "excused" => Status::Excused(detail.to_string()),
            "missing" => Status::Missing(detail.to_string()),
            other => panic!("line {}: unknown status {other:?}", i + 1),
        };
        assert!(out.insert(name.to_string(), status).is_none(), "line {}: {name} listed twice", i + 1);
    }
    out
}

fn words(s: Option<String>) -> BTreeSet<String> {
    s.unwrap_or_default().split_whitespace().map(str::to_string).collect()
}

/// Mesa's extensions on an ES 2.0 context: Mesa held to ES 2.0, with every other `MESA_*`
/// override cleared (this test binary runs nothing else, so the environment is its own).
fn mesa_extensions() -> Option<BTreeSet<String>> {
    for (k, _) in std::env::vars_os() {
        if k.to_string_lossy().starts_with("MESA_") {
            std::env::remove_var(k);
        }
    }
    std::env::set_var("MESA_GLES_VERSION_OVERRIDE", "2.0");
    let mut mesa = MesaGl::open_or_skip(W, H)?;
    let version = mesa.glGetString(GL_VERSION).expect("GL_VERSION").unwrap_or_default();
    assert!(version.starts_with("OpenGL ES 2.0"), "Mesa is not held to ES 2.0: {version}");
    Some(words(mesa.glGetString(GL_EXTENSIONS).expect("GL_EXTENSIONS")))
}

#[test]
fn the_parity_file_matches_both_extension_strings() {
    let file = parity_file();
    let Some(mesa) = mesa_extensions() else { return };
    let daemon = Daemon::start("extension-parity", &[]);
    let mut strata = strata_context(&daemon.socket, "extension-parity").expect("context");
    let ours = words(strata.glGetString(GL_EXTENSIONS).expect("GL_EXTENSIONS"));
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests");

    let mut wrong = Vec::new();
    for name in mesa.iter().filter(|n| !file.contains_key(*n)) {
        wrong.push(format!("{name}: Mesa offers it on ES 2.0, and the file has no line for it"));
    }
    for name in file.keys().filter(|n| !mesa.contains(*n)) {
        wrong.push(format!("{name}: listed, but Mesa does not offer it on ES 2.0"));
    }
    for name in ours.iter().filter(|n| !mesa.contains(*n)) {
        wrong.push(format!("{name}: Strata advertises it, and Mesa does not offer it on ES 2.0"));
    }
    for (name, status) in &file {
        let advertised = ours.contains(name);
        match status {
            Status::Advertised(files) => {
                if !advertised {
                    wrong.push(format!("{name}: listed as advertised, and Strata does not advertise it"));
                }
                let bare = name.trim_start_matches("GL_");
                for f in files {
                    match std::fs::read_to_string(tests.join(f)) {
                        Ok(src) if src.contains(bare) => {}
                        Ok(_) => wrong.push(format!("{name}: tests/{f} does not mention {bare}")),
                        Err(e) => wrong.push(format!("{name}: tests/{f}: {e}")),
                    }
                }
            }
            Status::Excused(_) | Status::Missing(_) if advertised => {
                wrong.push(format!("{name}: Strata advertises it, and the file says it does not"))
            }
            _ => {}
        }
    }
    assert!(wrong.is_empty(), "tests/extension_parity.txt is out of date:\n{}", wrong.join("\n"));

    let count = |f: fn(&Status) -> bool| file.values().filter(|s| f(s)).count();
    eprintln!(
        "Mesa offers {} extensions on ES 2.0: Strata advertises {}, {} excused, {} missing",
        mesa.len(),
        count(|s| matches!(s, Status::Advertised(_))),
        count(|s| matches!(s, Status::Excused(_))),
        count(|s| matches!(s, Status::Missing(_))),
    );
}

/// The GL and EGL extension strings of a pbuffer context made through the drop-in library.
fn library_extensions(socket: &Path) -> (BTreeSet<String>, BTreeSet<String>) {
    use std::ffi::{c_char, c_void, CStr};
    type Ptr = *mut c_void;
    // SAFETY: set before this test loads the library, which reads it at eglInitialize; the
    // other test of this binary reads no STRATA_ variable.
    unsafe { std::env::set_var("STRATA_SOCKET", socket) };
    let tmp = support::TempDir::new("extension-scope");
    // SAFETY: loading the drop-in library runs no initialisers that need anything from the test.
    let lib = unsafe { libloading::Library::new(support::shim_dir(&tmp).join("libEGL.so.1")) }.expect("the library");
    let text = |p: *const c_char| {
        // SAFETY: a non-null answer of eglQueryString or glGetString is NUL-terminated.
        words((!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()))
    };
    // SAFETY: EGL's and GLES2's prototypes; every out-pointer has room for what it gets.
    unsafe {
        let get_display: libloading::Symbol<unsafe extern "C" fn(Ptr) -> Ptr> =
            lib.get(b"eglGetDisplay\0").expect("eglGetDisplay");
        let init: libloading::Symbol<unsafe extern "C" fn(Ptr, *mut i32, *mut i32) -> u32> =
            lib.get(b"eglInitialize\0").expect("eglInitialize");
        let query: libloading::Symbol<unsafe extern "C" fn(Ptr, i32) -> *const c_char> =
            lib.get(b"eglQueryString\0").expect("eglQueryString");
        let choose: libloading::Symbol<unsafe extern "C" fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32> =
            lib.get(b"eglChooseConfig\0").expect("eglChooseConfig");
        let pbuffer: libloading::Symbol<unsafe extern "C" fn(Ptr, Ptr, *const i32) -> Ptr> =
            lib.get(b"eglCreatePbufferSurface\0").expect("eglCreatePbufferSurface");
        let create: libloading::Symbol<unsafe extern "C" fn(Ptr, Ptr, Ptr, *const i32) -> Ptr> =
            lib.get(b"eglCreateContext\0").expect("eglCreateContext");
        let make_current: libloading::Symbol<unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32> =
            lib.get(b"eglMakeCurrent\0").expect("eglMakeCurrent");
        let get_string: libloading::Symbol<unsafe extern "C" fn(u32) -> *const c_char> =
            lib.get(b"glGetString\0").expect("glGetString");
        let dpy = get_display(std::ptr::null_mut());
        assert!(init(dpy, std::ptr::null_mut(), std::ptr::null_mut()) != 0, "eglInitialize");
        let egl = text(query(dpy, 0x3055));
        let attribs = [0x3033, 1, 0x3040, 4, 0x3038];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        assert!(choose(dpy, attribs.as_ptr(), &mut config, 1, &mut n) != 0 && n == 1, "an ES 2.0 pbuffer config");
        let surface = pbuffer(dpy, config, [0x3057, 4, 0x3056, 4, 0x3038].as_ptr());
        let ctx = create(dpy, config, std::ptr::null_mut(), [0x3098, 2, 0x3038].as_ptr());
        assert!(make_current(dpy, surface, surface, ctx) != 0, "a current context");
        let gl = text(get_string(GL_EXTENSIONS));
        (gl, egl)
    }
}

#[test]
fn piglit_scope_holds_every_advertised_extension() {
    let daemon = Daemon::start("extension-scope", &[]);
    let (gl, egl) = library_extensions(Path::new(&daemon.socket));
    assert!(!gl.is_empty() && !egl.is_empty(), "no extension strings: GL {gl:?}, EGL {egl:?}");
    let outside: Vec<&String> =
        gl.iter().chain(&egl).filter(|e| !verdict::IN_SCOPE_EXTENSIONS.contains(&e.as_str())).collect();
    assert!(
        outside.is_empty(),
        "advertised, and missing from IN_SCOPE_EXTENSIONS in tests/piglit/verdict.rs (an exception could excuse a test of them): {outside:?}"
    );
    eprintln!("{} GL and {} EGL extensions advertised, all in piglit's scope", gl.len(), egl.len());
}

/// The mutation table (`tests/mutants/extensions.tsv`, for `tools/extension-mutants`) has one
/// line for each extension the parity file marks advertised, and names at least one test run
/// for each.
#[test]
fn the_mutation_table_covers_every_advertised_extension() {
    let file = parity_file();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/mutants/extensions.tsv");
    let text = std::fs::read_to_string(&path).expect("tests/mutants/extensions.tsv");
    let mut listed = BTreeSet::new();
    for line in text.lines().filter(|l| !l.starts_with('#') && !l.trim().is_empty()) {
        let mut fields = line.split('\t');
        let (name, runs) = (fields.next().unwrap_or_default(), fields.next().unwrap_or_default());
        assert!(!runs.trim().is_empty(), "tests/mutants/extensions.tsv: {name} names no test run");
        assert!(listed.insert(name.to_string()), "tests/mutants/extensions.tsv: {name} listed twice");
    }
    let advertised: BTreeSet<String> =
        file.iter().filter(|(_, s)| matches!(s, Status::Advertised(_))).map(|(n, _)| n.clone()).collect();
    let missing: Vec<_> = advertised.difference(&listed).collect();
    let extra: Vec<_> = listed.difference(&advertised).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "tests/mutants/extensions.tsv: no line for {missing:?}; lines for extensions not advertised: {extra:?}"
    );
}
