//! Fuzzes the style reader: any text, no panic. A style it accepts must
//! pass validation again and save to RON that loads back.

#![no_main]

use std::path::Path;

use helixhair_app::Style;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    // Lossy: what a user can feed is text, and every text is reachable.
    let text = String::from_utf8_lossy(data);
    let path = Path::new("fuzz.ron");
    let Ok(style) = Style::from_ron(&text, path) else {
        return;
    };
    if let Err(issue) = style.validate() {
        panic!("accepted, then invalid: {issue}");
    }
    let _ = style.strand_count();
    let saved = style.to_ron().expect("an accepted style saves");
    if let Err(error) = Style::from_ron(&saved, path) {
        panic!("a saved style does not load back: {error}\n{saved}");
    }
});
