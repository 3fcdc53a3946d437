pub fn volume(){}
