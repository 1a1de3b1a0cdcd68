function e = ehl_element(kind, varargin)
%EHL_ELEMENT  A bearing force element.
%   E = EHL_ELEMENT('hertz', C)          dry Hertz laws of case C
%   E = EHL_ELEMENT('fitted', C, REPORT) fitted laws of a characterization report (a file
%                                        name, or JSON text) for the bearing of case C
%   E = EHL_ELEMENT(CH)                  fitted laws of a characterization (EHL_CHARACTERIZE)
%   E = EHL_ELEMENT('trend', TRENDS)     a study's trend curves (trends.json file or JSON text)
%   E is a struct: id, type, kind ('dry' | 'fitted' | 'trend'), has_damping, ball_count,
%   ball_diameter_m, pitch_diameter_m, state (the element's own warm-start state, used by
%   EHL_EVALUATE unless another is given). Release it with EHL_FREE.
if isstruct(kind)
  e = ehl_mex('element_characterization', kind);
  return
end
switch kind
  case 'hertz'
    e = ehl_mex('element_hertz', varargin{1});
  case 'fitted'
    r = varargin{2};
    if exist(r, 'file') == 2
      e = ehl_mex('element_report_file', varargin{1}, r);
    else
      e = ehl_mex('element_report_json', varargin{1}, r);
    end
  case 'trend'
    t = varargin{1};
    if exist(t, 'file') == 2
      e = ehl_mex('element_trend_file', t);
    else
      e = ehl_mex('element_trend_json', t);
    end
  otherwise
    error('ehl:usage', 'ehl_element: kind ''%s'' is not hertz, fitted or trend', kind);
end
end
