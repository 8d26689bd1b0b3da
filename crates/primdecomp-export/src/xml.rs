//! A small element writer over `quick-xml` for the MJCF and URDF exports: attribute
//! values are escaped by quick-xml (names with quotes or angle brackets stay
//! well-formed), two-space indentation, deterministic attribute order (as given).

use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};
use quick_xml::Writer;

pub struct Xml {
    w: Writer<Vec<u8>>,
}

impl Xml {
    pub fn new() -> Xml {
        let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
        // Writing into a Vec cannot fail.
        let _ = w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)));
        Xml { w }
    }

    fn start_tag<'a>(tag: &'a str, attrs: &[(&str, &str)]) -> BytesStart<'a> {
        let mut e = BytesStart::new(tag);
        for (k, v) in attrs {
            e.push_attribute((*k, *v));
        }
        e
    }

    /// `<tag a="…">`.
    pub fn open(&mut self, tag: &str, attrs: &[(&str, &str)]) {
        let _ = self
            .w
            .write_event(Event::Start(Self::start_tag(tag, attrs)));
    }

    /// `</tag>`.
    pub fn close(&mut self, tag: &str) {
        let _ = self.w.write_event(Event::End(BytesEnd::new(tag)));
    }

    /// `<tag a="…"/>`.
    pub fn empty(&mut self, tag: &str, attrs: &[(&str, &str)]) {
        let _ = self
            .w
            .write_event(Event::Empty(Self::start_tag(tag, attrs)));
    }

    /// `<!-- text -->` (`--` in the text is broken up, as XML requires).
    pub fn comment(&mut self, text: &str) {
        let t = format!(" {} ", text.replace("--", "- -"));
        let _ = self
            .w
            .write_event(Event::Comment(quick_xml::events::BytesText::from_escaped(
                t,
            )));
    }

    pub fn finish(self) -> String {
        let mut s = String::from_utf8(self.w.into_inner()).unwrap_or_default();
        s.push('\n');
        s
    }
}

/// Numbers joined by spaces.
pub fn nums(xs: &[f64]) -> String {
    xs.iter()
        .map(|&x| super::engine::num(x))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attributes_are_escaped() {
        let mut x = Xml::new();
        x.open("a", &[("name", "q\"<b>&'")]);
        x.empty("b", &[("v", "1 2")]);
        x.comment("x -- y");
        x.close("a");
        let s = x.finish();
        assert!(s.contains(r#"name="q&quot;&lt;b&gt;&amp;&apos;""#), "{s}");
        assert!(s.contains("<!-- x - - y -->"), "{s}");
    }
}
